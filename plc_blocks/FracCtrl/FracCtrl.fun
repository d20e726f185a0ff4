(* FracCtrl: fractional-order and LQG control blocks on libfrac.
   Interface convention (PLCopen Enable type): Enable TRUE runs the block;
   a rising edge of Enable or of Update (re)loads Parameters; Active or
   Valid TRUE = outputs usable; Busy TRUE while enabled and working; Error
   TRUE with StatusID (FracCtrl.var) on a failure; Enable FALSE resets the
   outputs and sets StatusID = fracSTAT_DISABLED. *)

FUNCTION_BLOCK Watchdog (*Stale-sensor detection and fault reaction: on a stale sensor or a non-finite torque the torque ramps to zero (seed 004, 8.6 HIL notes: IMU over asynchronous CAN)*)
	VAR_INPUT
		Enable : BOOL; (*Run the block*)
		Parameters : WatchdogParType; (*Limits and ramp*)
		Update : BOOL; (*Rising edge: take over Parameters*)
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
