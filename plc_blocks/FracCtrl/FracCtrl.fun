(* FracCtrl: fractional-order and LQG control blocks on libfrac.
   Interface convention (PLCopen Enable type): Enable TRUE runs the block;
   a rising edge of Enable or of Update (re)loads Parameters; Active or
   Valid TRUE = outputs usable; Busy TRUE while enabled and working; Error
   TRUE with StatusID (FracCtrl.var) on a failure; Enable FALSE resets the
   outputs and sets StatusID = fracSTAT_DISABLED. Update is declared right
   after Enable (TrajLUT: then Run and Restart), so that a body reads the
   BOOL pins deciding its steady path in one load (fracctrl_status.h). *)

FUNCTION_BLOCK Watchdog (*Stale-sensor detection and fault reaction: on a stale sensor or a non-finite torque the torque ramps to zero (seed 004, 8.6 HIL notes: IMU over asynchronous CAN)*)
	VAR_INPUT
		Enable : BOOL; (*Run the block*)
		Update : BOOL; (*Rising edge: take over Parameters*)
		Parameters : WatchdogParType; (*Limits and ramp*)
		SampleCounter : UDINT; (*Incremented by the sensor task for every new sample*)
		TorqueIn : REAL; (*Torque setpoint from the controller [Nm]*)
		Acknowledge : BOOL; (*Rising edge: clear a latched fault once the sensor is fresh*)
	END_VAR
	VAR_OUTPUT
		Active : BOOL; (*Monitoring, no fault: TorqueOut = TorqueIn*)
		Busy : BOOL; (*Enabled and executing*)
		Error : BOOL; (*Fault latched or parameters invalid*)
		StatusID : UINT; (*fracSTAT_OK, fracERR_SENSOR_STALE, fracERR_TORQUE_NONFINITE, fracERR_PARAM, fracSTAT_DISABLED*)
		TorqueOut : REAL; (*Torque setpoint to the drive [Nm]*)
		Stale : BOOL; (*No new sample for more than MaxStaleCycles cycles*)
		StaleCycles : UDINT; (*Consecutive cycles without a new sample*)
		RampActive : BOOL; (*Fault reaction running: TorqueOut ramps to zero*)
	END_VAR
	VAR
		Internal : WatchdogInternalType;
	END_VAR
END_FUNCTION_BLOCK

FUNCTION_BLOCK LUT1D (*1-D lookup table y = f(x), linear or monotone cubic (frac/lut.h); feedforward tables of seed 004 Sec. 6.4*)
	VAR_INPUT
		Enable : BOOL;
		Update : BOOL; (*Rising edge: take over Parameters*)
		Parameters : LUT1DParType;
		X : REAL; (*Query point*)
	END_VAR
	VAR_OUTPUT
		Valid : BOOL; (*Y is valid (also when clamped or extrapolated)*)
		Busy : BOOL;
		Error : BOOL;
		StatusID : UINT; (*fracSTAT_OK, fracWRN_CLAMPED, 52002 extrapolated, fracERR_NONFINITE (Y holds), 51xxx parameter errors*)
		Y : REAL; (*Interpolated value*)
	END_VAR
	VAR
		Fb : FracFbStateType;
		Lut : FracLut1Obj;
	END_VAR
END_FUNCTION_BLOCK

FUNCTION_BLOCK LUT2D (*2-D bilinear lookup table y = f(x1, x2) (frac/lut.h)*)
	VAR_INPUT
		Enable : BOOL;
		Update : BOOL;
		Parameters : LUT2DParType;
		X1 : REAL;
		X2 : REAL;
	END_VAR
	VAR_OUTPUT
		Valid : BOOL;
		Busy : BOOL;
		Error : BOOL;
		StatusID : UINT; (*as LUT1D*)
		Y : REAL;
	END_VAR
	VAR
		Fb : FracFbStateType;
		Lut : FracLut2Obj;
	END_VAR
END_FUNCTION_BLOCK

FUNCTION_BLOCK FrictionComp (*Static friction compensation torque (seed 004 (5.2)-(5.4), sgn replaced by tanh(K v)) (frac/friction.h)*)
	VAR_INPUT
		Enable : BOOL;
		Update : BOOL;
		Parameters : FrictionCompParType;
		Velocity : REAL; (*Motor velocity, driven side [rad/s]*)
	END_VAR
	VAR_OUTPUT
		Valid : BOOL;
		Busy : BOOL;
		Error : BOOL;
		StatusID : UINT; (*fracSTAT_OK, fracERR_NONFINITE (Torque holds), fracERR_PARAM*)
		Torque : REAL; (*Friction torque estimate [Nm], added to the setpoint*)
	END_VAR
	VAR
		Fb : FracFbStateType;
		Out : FracReal; (*libfrac torque of the last call*)
		Friction : FracFrictionObj;
	END_VAR
END_FUNCTION_BLOCK

FUNCTION_BLOCK LQGDelay (*State-difference LQG with delay registers and friction state (seed 004 (6.45), (7.18)-(7.27)) (frac/lqg.h)*)
	VAR_INPUT
		Enable : BOOL;
		Update : BOOL; (*Rising edge: take over Parameters (the estimate restarts at 0)*)
		Parameters : LQGDelayParType;
		Reset : BOOL; (*Rising edge: estimate back to 0*)
		UStar : REAL; (*Feedforward torque, already sent Di samples early [Nm]*)
		YRef : ARRAY[0..2] OF REAL; (*References of the measured outputs, delayed ones delayed by Do*)
		Y : ARRAY[0..2] OF REAL; (*Measurements as received*)
	END_VAR
	VAR_OUTPUT
		Valid : BOOL;
		Busy : BOOL;
		Error : BOOL;
		StatusID : UINT; (*fracSTAT_OK, 52003 a measurement skipped, fracERR_NONFINITE (U holds), 51xxx parameter errors, fracERR_PARAM (P out of range)*)
		U : REAL; (*Torque command u_bar = u* + K e_x - e_z [Nm]*)
		FrictionEstimate : REAL; (*z_hat, the friction torque the law compensates [Nm]*)
	END_VAR
	VAR
		Fb : FracFbStateType;
		ResetOld : BOOL;
		Bank : UDINT; (*Storage bank of the object in effect*)
		Lqg : FracLqgObj;
		Storage : ARRAY[0..1, 0..fracLQG_STORAGE_LEN] OF FracReal; (*Two banks: a new set is built in the other one*)
	END_VAR
END_FUNCTION_BLOCK

FUNCTION_BLOCK TrajLUT (*Trajectory playback with per-channel lead/lag (seed 004 Sec. 6.4, 8.6) (frac/trajlut.h)*)
	VAR_INPUT
		Enable : BOOL;
		Update : BOOL; (*Rising edge: take over Parameters (playback restarts at cycle 0)*)
		Run : BOOL; (*TRUE: advance one cycle per call (the thesis's run-time counter); FALSE: hold the current cycle*)
		Restart : BOOL; (*Rising edge: back to cycle 0*)
		Parameters : TrajLUTParType;
	END_VAR
	VAR_OUTPUT
		Valid : BOOL;
		Busy : BOOL;
		Error : BOOL;
		StatusID : UINT; (*fracSTAT_OK, fracWRN_CLAMPED (outside the table: end values), 51xxx parameter errors*)
		Y : ARRAY[0..7] OF REAL; (*Channel values at (Cycle + Lead) Ts*)
		Segment : FracTrajSegmentEnum;
		Cycle : UDINT; (*Cycle k the outputs belong to*)
	END_VAR
	VAR
		Fb : FracFbStateType;
		RestartOld : BOOL;
		SteadyPins : UDINT; (*Enable + 256 (Update + 256 (Run + 256 Restart)) of a call that only plays (Fb steady, Restart unchanged), 0 otherwise*)
		Out : ARRAY[0..7] OF FracReal; (*libfrac values of the last call; the channels the set in effect does not play hold Y*)
		OutSegment : DINT; (*libfrac segment of the last call*)
		Traj : FracTrajLutObj;
	END_VAR
END_FUNCTION_BLOCK

FUNCTION_BLOCK ParTable (*Validates the binary parameter table emitted by fracdesign table: magic, version, size, CRC32, layout, dimensions, finiteness (frac/ptable.h)*)
	VAR_INPUT
		Enable : BOOL; (*Rising edge: validate the data object*)
		Update : BOOL; (*Rising edge: validate again (a new data object was loaded)*)
		pData : REFERENCE TO USINT; (*Bytes of the data object*)
		Size : UDINT; (*Bytes available at pData*)
	END_VAR
	VAR_OUTPUT
		Valid : BOOL; (*The table passed every check; Handle may be read*)
		Busy : BOOL;
		Error : BOOL;
		StatusID : UINT; (*fracSTAT_OK, fracERR_TABLE_*, fracERR_LIBFRAC + 5 dimensions, fracERR_NONFINITE, fracERR_NULL*)
		Entries : UDINT; (*Entries in the directory*)
		FailEntry : DINT; (*Directory index of the failing entry, -1 = header*)
		FailField : STRING[31]; (*Field that failed ("magic", "crc32", "entry.rows", ...)*)
	END_VAR
	VAR
		Fb : FracFbStateType;
		Handle : FracPtableObj; (*Validated table, read by the program with frac_ptable_get*)
	END_VAR
END_FUNCTION_BLOCK

FUNCTION_BLOCK FracOp (*Fractional operator s^r with a choice of realization: GL, Oustaloup, refined Oustaloup, CFE (frac/fo_op.h)*)
	VAR_INPUT
		Enable : BOOL;
		Update : BOOL; (*Rising edge: take over Parameters (state restarts at 0)*)
		Parameters : FracOpParType;
		Reset : BOOL; (*Rising edge: zero input history*)
		X : REAL; (*Input*)
	END_VAR
	VAR_OUTPUT
		Valid : BOOL;
		Busy : BOOL;
		Error : BOOL;
		StatusID : UINT; (*fracSTAT_OK, fracERR_NONFINITE (Y holds), 51004 storage too small, 51006 order, 51007 band, 51008 sample time, fracERR_PARAM*)
		Y : REAL; (*s^r X*)
	END_VAR
	VAR
		Fb : FracFbStateType;
		ResetOld : BOOL;
		Bank : UDINT; (*Storage bank of the realization in effect*)
		Op : FracFoObj;
		Storage : ARRAY[0..1, 0..fracFO_STORAGE_LEN] OF FracReal; (*Two banks: a new set is built in the other one*)
	END_VAR
END_FUNCTION_BLOCK

FUNCTION_BLOCK FOPID (*Fractional PI^lambda D^mu controller with derivative filter, limits, anti-windup and manual mode; FO-PI, FO-PD and the Delta = 1/K variant of seed 001 (frac/fopid.h)*)
	VAR_INPUT
		Enable : BOOL;
		Update : BOOL; (*Rising edge: take over Parameters (state restarts at 0)*)
		Parameters : FOPIDParType;
		Reset : BOOL; (*Rising edge: zero state*)
		W : REAL; (*Set point*)
		X : REAL; (*Actual value*)
		Manual : BOOL; (*TRUE: Y = Y_manual; switching back to automatic is bumpless*)
		Y_manual : REAL;
	END_VAR
	VAR_OUTPUT
		Valid : BOOL;
		Busy : BOOL;
		Error : BOOL;
		StatusID : UINT; (*fracSTAT_OK, fracWRN_SATURATED, fracERR_NONFINITE (Y holds), 51006 order, 51009 gain, 51010 limits, fracERR_PARAM, 51004 storage*)
		Y : REAL; (*Controller output*)
		Saturated : BOOL; (*Y at Y_min or Y_max*)
	END_VAR
	VAR
		Fb : FracFbStateType;
		ResetOld : BOOL;
		ManualOld : BOOL;
		Bank : UDINT;
		Pid : FracFopidObj;
		Storage : ARRAY[0..1, 0..fracFOPID_STORAGE_LEN] OF FracReal; (*Two banks: a new set is built in the other one*)
	END_VAR
END_FUNCTION_BLOCK

FUNCTION_BLOCK FracDamp (*Collocated fractional damping law with prefilter, seed 002: Y = F(s) W - C(s) X (frac/fodamp.h)*)
	VAR_INPUT
		Enable : BOOL;
		Update : BOOL; (*Rising edge: take over Parameters (state restarts at 0)*)
		Parameters : FracDampParType;
		Reset : BOOL; (*Rising edge: zero state*)
		W : REAL; (*Reference: tip angle theta_2^* [rad]*)
		X : REAL; (*Collocated measurement: base moment Gamma_c [Nm]*)
	END_VAR
	VAR_OUTPUT
		Valid : BOOL;
		Busy : BOOL;
		Error : BOOL;
		StatusID : UINT; (*fracSTAT_OK, fracERR_NONFINITE (Y holds), 51005 M > 2, 51006 order, 51009 gain, 51014 D not Hurwitz, 51008 sample time, 51004 storage*)
		Y : REAL; (*Motor reference theta_m* [rad]*)
	END_VAR
	VAR
		Fb : FracFbStateType;
		ResetOld : BOOL;
		Bank : UDINT; (*Object and storage bank in effect*)
		Damp : ARRAY[0..1] OF FracFodampObj; (*Two objects: frac_fodamp refers to its own coefficients, so a new set is built in place in the other one*)
		Storage : ARRAY[0..1, 0..fracFODAMP_STORAGE_LEN] OF FracReal;
	END_VAR
END_FUNCTION_BLOCK
