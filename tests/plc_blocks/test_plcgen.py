#!/usr/bin/env python3
"""Tests of plc_blocks/tools/plcgen.py: the generated header follows the
IEC 61131-3 declarations field by field, compiles, and every malformed
declaration is rejected with FILE:LINE and a message naming the problem.

usage: test_plcgen.py PATH/TO/plcgen.py"""
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest

GEN = None
INCLUDE = None

LBY = """<?xml version="1.0" encoding="utf-8"?>
<Library Version="1.0.0" SubType="ANSIC" xmlns="http://br-automation.co.at/AS/Library">
  <Files>
    <File>Lib.typ</File>
    <File>Lib.var</File>
    <File>Lib.fun</File>
    <File>Gain.c</File>
  </Files>
</Library>
"""
TYP = """(* types *)
TYPE
	GainParType : STRUCT (*parameters*)
		K : REAL; (*gain*)
		Table : ARRAY[0..lenTAB] OF LREAL; (*table*)
		Grid : ARRAY[1..2, 0..2] OF INT;
	END_STRUCT;
	ModeEnum : (
		modeOFF := 0, (*off*)
		modeON, (*on*)
		modeHOLD := 7
	);
	Counts : UDINT;
	Real : LREAL; (*C: double "math.h"; C type*)
	ObjStore : ARRAY[0..1] OF LREAL; (*C: two_words "obj.h"; storage*)
END_TYPE
"""
VAR = """VAR CONSTANT
	lenTAB : UINT := 3; (*last index*)
	errX : UINT := 16#FFFE;
	kNeg : DINT := -5;
	kPi : REAL := 3.14;
	kOn : BOOL := TRUE;
END_VAR
"""
FUN = """FUNCTION_BLOCK Gain (*a gain*)
	VAR_INPUT
		Enable : BOOL;
		Parameters : GainParType;
		U : REAL; (*input*)
		Name : STRING[10];
	END_VAR
	VAR_OUTPUT
		Y : REAL;
		Mode : ModeEnum;
		N : Counts;
	END_VAR
	VAR
		Acc : Real;
		pTab : REFERENCE TO LREAL;
		Obj : ObjStore;
	END_VAR
END_FUNCTION_BLOCK
"""


class Lib:
    def __init__(self, **over):
        self.dir = tempfile.mkdtemp(prefix="plcgen")
        files = {"ANSIC.lby": LBY, "Lib.typ": TYP, "Lib.var": VAR, "Lib.fun": FUN,
                 "Gain.c": "/* body */\n"}
        self.inc = tempfile.mkdtemp(prefix="plcgen_inc")
        with open(os.path.join(self.inc, "obj.h"), "w") as fh:
            fh.write(over.pop("obj_h", "typedef struct two_words { double a; void *p; } two_words;\n"))
        files.update(over)
        for name, text in files.items():
            if text is not None:
                with open(os.path.join(self.dir, name), "w") as fh:
                    fh.write(text)

    def run(self, *opts):
        out = os.path.join(self.dir, "out.h")
        p = subprocess.run([sys.executable, GEN] + list(opts) + [os.path.join(self.dir, "ANSIC.lby"), out],
                           capture_output=True, text=True)
        header = None
        if p.returncode == 0:
            with open(out) as fh:
                header = fh.read()
        return p.returncode, p.stderr, header

    def compile(self, *flags):
        """Compiles a translation unit that includes the generated header; returns (rc, stderr)."""
        src = os.path.join(self.dir, "use.c")
        with open(src, "w") as fh:
            fh.write('#include "out.h"\nint main(void) { struct Gain g; g.Y = 0.0f; Gain(&g); return (int)g.Y; }\n'
                     'void Gain(struct Gain* inst) { inst->Y = inst->U * inst->Parameters.K; }\n')
        p = subprocess.run(["cc", "-std=c89", "-pedantic", "-Wall", "-Wextra", "-Werror", "-fsyntax-only",
                            "-I" + INCLUDE, "-I" + self.dir, "-I" + self.inc] + list(flags) + [src],
                           capture_output=True, text=True)
        return p.returncode, p.stderr

    def close(self):
        shutil.rmtree(self.dir)
        shutil.rmtree(self.inc)


class GoodDeclarations(unittest.TestCase):
    def setUp(self):
        self.lib = Lib()
        self.rc, self.err, self.h = self.lib.run()
        self.assertEqual(self.rc, 0, self.err)

    def tearDown(self):
        self.lib.close()

    def test_struct_fields_in_declaration_order_with_arrays(self):
        body = re.search(r"typedef struct GainParType \{.*?\n(.*?)\} GainParType;", self.h, re.S).group(1)
        fields = [l.split(";")[0].strip() for l in body.strip().splitlines()]
        self.assertEqual(fields, ["REAL K", "LREAL Table[4]", "INT Grid[2][3]"])

    def test_function_block_sections_follow_the_fun_file(self):
        body = re.search(r"typedef struct Gain \{\n(.*?)\} Gain_typ;", self.h, re.S).group(1)
        decls = [l.split(";")[0].strip() for l in body.splitlines() if ";" in l]
        self.assertEqual(decls, ["BOOL Enable", "GainParType Parameters", "REAL U", "plcstring Name[11]",
                                 "REAL Y", "ModeEnum Mode", "Counts N", "Real Acc",
                                 "LREAL * pTab", "ObjStore Obj"])
        self.assertIn("void Gain(struct Gain* inst);", self.h)

    def test_enum_values_continue_after_explicit_ones(self):
        self.assertRegex(self.h, r"modeOFF = 0,.*\n\s*modeON = 1,.*\n\s*modeHOLD = 7")

    def test_constants_keep_type_and_value(self):
        self.assertIn("#define errX ((UINT)65534U)", self.h)
        self.assertIn("#define kNeg ((DINT)(-5))", self.h)
        self.assertIn("#define kPi ((REAL)3.14f)", self.h)
        self.assertIn("#define kOn ((BOOL)1)", self.h)

    def test_c_tag_includes_its_header_and_keeps_the_iec_type(self):
        self.assertIn('#include "math.h"', self.h)
        self.assertIn("typedef LREAL Real; /* C type */", self.h)
        self.assertIn("typedef LREAL ObjStore[2]; /* storage */", self.h)
        self.assertIn("#define ObjStore_C(obj) ((two_words *)(void *)(obj))", self.h)

    def test_comments_become_c_comments(self):
        self.assertIn("REAL U; /* input */", self.h)

    def test_generated_header_compiles_as_c89(self):
        rc, err = self.lib.compile()
        self.assertEqual(rc, 0, err)


class PlcopenExport(unittest.TestCase):
    """--plcopen writes the interface as TC6 XML: types, pins with their comments, constants, no body."""

    @classmethod
    def setUpClass(cls):
        import xml.etree.ElementTree as ET
        lib = Lib()
        try:
            xml_out = os.path.join(lib.dir, "lib.xml")
            rc, err, _ = lib.run("--plcopen", xml_out)
            assert rc == 0, err
            cls.root = ET.parse(xml_out).getroot()
        finally:
            lib.close()
        cls.ns = {"p": "http://www.plcopen.org/xml/tc6_0201", "x": "http://www.w3.org/1999/xhtml"}

    def find(self, path):
        return self.root.find(path, self.ns)

    def test_function_block_pins_in_sections_with_comments(self):
        fb = self.find(".//p:pou[@name='Gain']")
        self.assertEqual(fb.get("pouType"), "functionBlock")
        names = lambda sec: [v.get("name") for v in fb.findall("p:interface/p:%s/p:variable" % sec, self.ns)]
        self.assertEqual(names("inputVars"), ["Enable", "Parameters", "U", "Name"])
        self.assertEqual(names("outputVars"), ["Y", "Mode", "N"])
        self.assertEqual(names("localVars"), ["Acc", "pTab", "Obj"])
        u = fb.find("p:interface/p:inputVars/p:variable[@name='U']", self.ns)
        self.assertEqual(u.find("p:documentation/x:p", self.ns).text, "input")
        self.assertIsNotNone(u.find("p:type/p:REAL", self.ns))
        self.assertEqual(fb.find("p:interface/p:inputVars/p:variable[@name='Name']/p:type/p:string",
                                 self.ns).get("length"), "10")
        self.assertEqual(fb.find("p:interface/p:localVars/p:variable[@name='pTab']/p:type/p:pointer/p:baseType/p:LREAL",
                                 self.ns) is not None, True)

    def test_body_is_external_not_invented(self):
        fb = self.find(".//p:pou[@name='Gain']")
        self.assertIsNone(fb.find("p:body", self.ns))
        ext = fb.find("p:addData/p:data/{urn:fracarm:plcopen}externalBody", self.ns)
        self.assertEqual((ext.get("language"), ext.get("file")), ("ANSIC", "Gain.c"))

    def test_array_bounds_enum_values_and_constants(self):
        dims = self.find(".//p:dataType[@name='GainParType']//p:variable[@name='Grid']/p:type/p:array")
        self.assertEqual([(d.get("lower"), d.get("upper")) for d in dims.findall("p:dimension", self.ns)],
                         [("1", "2"), ("0", "2")])
        vals = self.find(".//p:dataType[@name='ModeEnum']/p:baseType/p:enum/p:values")
        self.assertEqual([(v.get("name"), v.get("value")) for v in vals], [("modeOFF", "0"), ("modeON", "1"),
                                                                           ("modeHOLD", "7")])
        c = self.find(".//p:globalVars[@constant='true']/p:variable[@name='errX']")
        self.assertEqual(c.find("p:initialValue/p:simpleValue", self.ns).get("value"), "16#FFFE")


PROG = """(* a program on Gain *)
PROGRAM UseGain (*doc of the program*)
	VAR_INPUT
		In : REAL; (*input of the program*)
		Go : BOOL;
	END_VAR
	VAR_OUTPUT
		Out : LREAL;
		Status : ModeEnum;
	END_VAR
	VAR
		G : Gain;
		Buf : ARRAY[0..3] OF LREAL;
		Count : UDINT := 2;
	END_VAR
	G.Parameters.K := 2.0;
	G.Parameters.Table[1] := Buf[Count];
	G(Enable := Go AND NOT (In > 1.5), U := In * 2.0, Mode => Status);
	IF G.Mode = ModeEnum#modeON THEN
		Out := G.Y;
	ELSIF Status = modeHOLD THEN
		Out := REAL_TO_LREAL(LIMIT(-1.0, G.Y, 1.0)) + Buf[0];
	ELSE
		Count := Count + UINT_TO_UDINT(lenTAB);
	END_IF;
END_PROGRAM
"""


class StPrograms(unittest.TestCase):
    """ST programs parse with the declaration parser and every call uses declared pins of the right type."""

    def check(self, prog):
        lib = Lib(**{"prog.st": prog})
        try:
            xml_out = os.path.join(lib.dir, "lib.xml")
            rc, err, _ = lib.run("--st", os.path.join(lib.dir, "prog.st"), "--plcopen", xml_out)
            xml_text = None
            if rc == 0:
                with open(xml_out) as fh:
                    xml_text = fh.read()
        finally:
            lib.close()
        return rc, err, xml_text

    def reject(self, pattern, old, new):
        self.assertIn(old, PROG)
        rc, err, _ = self.check(PROG.replace(old, new))
        self.assertEqual(rc, 1, "accepted: " + new)
        self.assertRegex(err, r"prog\.st:\d+: error: " + pattern)

    def test_good_program_passes_and_exports_its_interface(self):
        rc, err, xml_text = self.check(PROG)
        self.assertEqual(rc, 0, err)
        self.assertIn('pouType="program"', xml_text)
        self.assertIn('language="ST" file="prog.st"', xml_text)
        self.assertIn("input of the program", xml_text)

    def test_undeclared_pin(self):
        self.reject(r"'Gain2' is not an input of Gain", "U := In * 2.0", "Gain2 := In")

    def test_output_given_as_input(self):
        self.reject(r"'Y' is not an input of Gain", "U := In * 2.0", "Y := In")

    def test_pin_of_the_wrong_type(self):
        self.reject(r"input G\.U: REAL expected, found BOOL", "U := In * 2.0", "U := Go")

    def test_narrowing_needs_a_conversion(self):
        self.reject(r"assignment to 'In': REAL expected, found LREAL", "Out := G.Y;", "In := Out;")

    def test_internal_variable_is_not_a_pin(self):
        self.reject(r"'Acc' is not a pin of Gain", "Out := G.Y;", "Out := G.Acc;")

    def test_output_cannot_be_assigned(self):
        self.reject(r"output G\.Y cannot be assigned", "Out := G.Y;", "G.Y := 1.0;")

    def test_undeclared_variable(self):
        self.reject(r"'Nope' is not a declared variable", "Out := G.Y;", "Out := Nope;")

    def test_condition_must_be_bool(self):
        self.reject(r"condition: BOOL expected, found REAL", "IF G.Mode = ModeEnum#modeON THEN", "IF In THEN")

    def test_unknown_enumerator(self):
        self.reject(r"'ModeEnum#modeFAST' is not a declared enumerator", "ModeEnum#modeON", "ModeEnum#modeFAST")

    def test_output_pin_into_a_variable_of_another_type(self):
        self.reject(r"output G\.Mode: BOOL expected, found ModeEnum", "Mode => Status", "Mode => Go")


class LayoutChecks(unittest.TestCase):
    """The compile-time checks of a type naming a C type stop the build when the C type does not fit."""

    def build(self, typ=TYP, obj_h=None, opts=(), flags=()):
        over = {"Lib.typ": typ}
        if obj_h is not None:
            over["obj_h"] = obj_h
        lib = Lib(**over)
        try:
            rc, err, _ = lib.run(*opts)
            self.assertEqual(rc, 0, err)
            return lib.compile(*flags)
        finally:
            lib.close()

    def test_c_type_larger_than_the_storage_fails_to_compile(self):
        rc, err = self.build(obj_h="typedef struct two_words { double a, b, c; } two_words;\n")
        self.assertNotEqual(rc, 0)
        self.assertIn("ObjStore_holds_two_words", err)

    def test_storage_larger_than_needed_fails_on_the_reference_configuration(self):
        rc, err = self.build(typ=TYP.replace("ARRAY[0..1] OF LREAL; (*C: two_words", "ARRAY[0..2] OF LREAL; (*C: two_words"))
        self.assertNotEqual(rc, 0)
        self.assertIn("ObjStore_least_for_two_words", err)

    def test_c_type_more_aligned_than_the_storage_fails_to_compile(self):
        rc, err = self.build(typ=TYP.replace("ARRAY[0..1] OF LREAL; (*C: two_words", "ARRAY[0..3] OF UDINT; (*C: two_words"))
        self.assertNotEqual(rc, 0)
        self.assertIn("ObjStore_aligned_for_two_words", err)

    def test_elementary_alias_of_another_size_fails_to_compile(self):
        rc, err = self.build(typ=TYP.replace('Real : LREAL; (*C: double', 'Real : REAL; (*C: double'))
        self.assertNotEqual(rc, 0)
        self.assertIn("Real_size_of_double", err)

    def test_configuration_macro_selects_the_alias_type(self):
        typ = TYP.replace('(*C: double "math.h"; C type*)', '(*C: real_t "obj.h"; C type*)')
        obj_h = ("#ifdef SINGLE\ntypedef float real_t;\n#else\ntypedef double real_t;\n#endif\n"
                 "typedef struct two_words { double a; void *p; } two_words;\n")
        self.assertEqual(self.build(typ=typ, obj_h=obj_h, opts=("--config", "SINGLE:Real=REAL"),
                                    flags=("-DSINGLE",))[0], 0)
        self.assertEqual(self.build(typ=typ, obj_h=obj_h, opts=("--config", "SINGLE:Real=REAL"))[0], 0)
        rc, err = self.build(typ=typ, obj_h=obj_h, flags=("-DSINGLE",))
        self.assertNotEqual(rc, 0)
        self.assertIn("Real_size_of_real_t", err)


class MalformedDeclarations(unittest.TestCase):
    def reject(self, pattern, **files):
        lib = Lib(**files)
        try:
            rc, err, _ = lib.run()
        finally:
            lib.close()
        self.assertEqual(rc, 1, "accepted a malformed declaration")
        self.assertRegex(err, r"^\S+:\d+: error: ")
        self.assertRegex(err, pattern)

    def test_missing_semicolon_names_the_variable_and_line(self):
        self.reject(r"Lib\.fun:5: error: expected ';' after the declaration of 'U'",
                    **{"Lib.fun": FUN.replace("U : REAL; (*input*)", "U : REAL (*input*)")})

    def test_unknown_type(self):
        self.reject(r"unknown type 'REEL'", **{"Lib.fun": FUN.replace("U : REAL;", "U : REEL;")})

    def test_missing_end_var(self):
        self.reject(r"VAR_OUTPUT section of 'Gain' has no END_VAR",
                    **{"Lib.fun": FUN.replace("\t\tN : Counts;\n\tEND_VAR", "\t\tN : Counts;\n")})

    def test_duplicate_member(self):
        self.reject(r"'Y' declared twice in FUNCTION_BLOCK Gain",
                    **{"Lib.fun": FUN.replace("N : Counts;", "Y : REAL;")})

    def test_initial_value_in_block(self):
        self.reject(r"initial value for 'U' is not supported",
                    **{"Lib.fun": FUN.replace("U : REAL;", "U : REAL := 1.0;")})

    def test_reserved_word_as_a_name(self):
        self.reject(r"Lib\.fun:5: error: 'Reference' is a reserved word",
                    **{"Lib.fun": FUN.replace("U : REAL;", "Reference : REAL;")})

    def test_reference_without_to(self):
        self.reject(r"expected 'TO' after REFERENCE", **{"Lib.fun": FUN.replace("REFERENCE TO LREAL", "REFERENCE LREAL")})

    def test_unterminated_comment(self):
        self.reject(r"unterminated comment", **{"Lib.typ": TYP.replace("; storage*)", "; storage")})

    def test_inverted_array_range(self):
        self.reject(r"empty array range 3\.\.1", **{"Lib.typ": TYP.replace("1..2, 0..2", "3..1, 0..2")})

    def test_constant_out_of_range(self):
        self.reject(r"value 70000 out of range of UINT", **{"Lib.var": VAR.replace("16#FFFE", "70000")})

    def test_pragma_is_not_iec_and_refused(self):
        self.reject(r"Lib\.typ:\d+: error: pragma \{C double \"math\.h\"\} in type 'Real' is not IEC 61131-3",
                    **{"Lib.typ": TYP.replace('LREAL; (*C: double "math.h"; C type*)', '{C double "math.h"};')})

    def test_malformed_c_tag(self):
        self.reject(r"malformed C type tag in the comment of 'Real'",
                    **{"Lib.typ": TYP.replace('(*C: double "math.h"; C type*)', '(*C: double math.h C type*)')})

    def test_c_tag_on_a_struct_is_refused(self):
        self.reject(r"type 'GainParType' names the C type gain_t but is not an alias",
                    **{"Lib.typ": TYP.replace("(*parameters*)", '(*C: gain_t "g.h"; parameters*)')})

    def test_config_of_an_undeclared_alias_is_refused(self):
        lib = Lib()
        try:
            rc, err, _ = lib.run("--config", "SINGLE:Nope=REAL")
        finally:
            lib.close()
        self.assertEqual(rc, 1)
        self.assertIn("'Nope' is not a declared alias of an elementary type", err)

    def test_block_without_body(self):
        self.reject(r"function block 'Gain' has no body Gain\.c", **{"Gain.c": None,
                    "ANSIC.lby": LBY.replace("<File>Gain.c</File>", "")})

    def test_body_file_not_in_descriptor(self):
        self.reject(r"'Extra\.c' is in the library folder but not in the descriptor", **{"Extra.c": "/* */\n"})

    def test_listed_file_missing(self):
        self.reject(r"file 'Gain\.c' listed in the descriptor does not exist", **{"Gain.c": None})


class ShippedExamples(unittest.TestCase):
    """docs/st: every block has an ST example that calls it; ArmCtrl.st calls the blocks in the C order."""

    def setUp(self):
        sys.path.insert(0, os.path.dirname(GEN))
        import plcgen
        import stcheck
        self.plcgen, self.stcheck = plcgen, stcheck
        tools = os.path.dirname(os.path.abspath(GEN))
        self.root = os.path.dirname(os.path.dirname(tools))
        self.lib = plcgen.generate(os.path.join(self.root, "plc_blocks", "FracCtrl", "ANSIC.lby"))
        st = os.path.join(self.root, "docs", "st")
        self.files = sorted(os.path.join(st, f) for f in os.listdir(st) if f.endswith(".st"))

    def test_every_example_type_checks_and_every_block_is_called(self):
        progs = self.stcheck.parse_programs(self.lib, self.files)
        called = {fb for p in progs for _, fb in p["calls"]}
        self.assertEqual(called, set(self.lib.fbs))
        for fb in self.lib.fbs:
            self.assertIn(os.path.join(self.root, "docs", "st", fb + ".st"), self.files)

    def test_armctrl_st_calls_the_blocks_in_the_order_of_armctrl_c(self):
        prog = self.stcheck.parse_programs(self.lib, [os.path.join(self.root, "docs", "st", "ArmCtrl.st")])[0]
        with open(os.path.join(self.root, "plc_blocks", "programs", "ArmCtrl.c")) as fh:
            c = fh.read()
        body = re.search(r"static void run_blocks\(armctrl \*a\)\n\{(.*?)\n\}", c, re.S).group(1)
        c_calls = re.findall(r"\b(%s)\(&a->" % "|".join(self.lib.fbs), body)
        self.assertEqual([fb for _, fb in prog["calls"]], c_calls)
        self.assertEqual(len(c_calls), 5)


class ShippedLibrary(unittest.TestCase):
    def test_fracctrl_declarations_generate(self):
        root = os.path.dirname(os.path.dirname(os.path.abspath(GEN)))
        with tempfile.TemporaryDirectory() as d:
            p = subprocess.run([sys.executable, GEN, os.path.join(root, "FracCtrl", "ANSIC.lby"),
                                os.path.join(d, "FracCtrl.h")], capture_output=True, text=True)
            self.assertEqual(p.returncode, 0, p.stderr)


if __name__ == "__main__":
    GEN = os.path.abspath(sys.argv.pop(1))
    INCLUDE = os.path.join(os.path.dirname(os.path.dirname(GEN)), "include")
    unittest.main(verbosity=1)
