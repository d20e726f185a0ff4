#!/usr/bin/env python3
"""Tests of plc_blocks/tools/lbycheck.py: the shipped FracCtrl and libfrac
descriptors import together, and each way a descriptor can be wrong (file
missing, source not listed, dependency unresolved, wrong SubType) is refused
with a message naming it.

usage: test_lbycheck.py PATH/TO/lbycheck.py PROJECT_SOURCE_DIR"""
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

TOOL = ROOT = None

LBY = """<?xml version="1.0" encoding="utf-8"?>
<Library Version="1.0.0" SubType="ANSIC" xmlns="http://br-automation.co.at/AS/Library">
  <Files>
    <File>src/a.c</File>
    <File>include/a.h</File>
  </Files>
  <Dependencies>
    <Dependency ObjectName="Base" />
  </Dependencies>
</Library>
"""
BASE = """<?xml version="1.0" encoding="utf-8"?>
<Library Version="1.0.0" SubType="ANSIC" xmlns="http://br-automation.co.at/AS/Library">
  <Files><File>b.c</File></Files>
</Library>
"""


def run(*dirs):
    p = subprocess.run([sys.executable, TOOL] + list(dirs), capture_output=True, text=True)
    return p.returncode, p.stdout + p.stderr


class Descriptors(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix="lbycheck")
        self.lib, self.base = os.path.join(self.tmp, "Lib"), os.path.join(self.tmp, "Base")
        for path, text in ((os.path.join(self.lib, "ANSIC.lby"), LBY), (os.path.join(self.lib, "src", "a.c"), ""),
                           (os.path.join(self.lib, "include", "a.h"), ""),
                           (os.path.join(self.base, "ANSIC.lby"), BASE), (os.path.join(self.base, "b.c"), "")):
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, "w") as fh:
                fh.write(text)

    def tearDown(self):
        shutil.rmtree(self.tmp)

    def test_consistent_pair_passes(self):
        rc, out = run(self.lib, self.base)
        self.assertEqual(rc, 0, out)
        self.assertIn("Lib: 2 files listed", out)

    def test_listed_file_missing(self):
        os.remove(os.path.join(self.lib, "include", "a.h"))
        rc, out = run(self.lib, self.base)
        self.assertEqual(rc, 1)
        self.assertIn("'include/a.h' is listed but does not exist", out)

    def test_source_not_listed(self):
        open(os.path.join(self.lib, "src", "extra.c"), "w").close()
        rc, out = run(self.lib, self.base)
        self.assertEqual(rc, 1)
        self.assertIn("'src/extra.c' is in the library but not in the descriptor", out)

    def test_dependency_unresolved(self):
        rc, out = run(self.lib)
        self.assertEqual(rc, 1)
        self.assertIn("dependency 'Base' does not resolve", out)

    def test_wrong_subtype(self):
        with open(os.path.join(self.base, "ANSIC.lby"), "w") as fh:
            fh.write(BASE.replace('SubType="ANSIC"', 'SubType="IEC"'))
        rc, out = run(self.lib, self.base)
        self.assertEqual(rc, 1)
        self.assertIn("SubType is 'IEC', expected \"ANSIC\"", out)


class Shipped(unittest.TestCase):
    def test_fracctrl_and_libfrac_import_together(self):
        rc, out = run(os.path.join(ROOT, "plc_blocks", "FracCtrl"), os.path.join(ROOT, "libfrac"))
        self.assertEqual(rc, 0, out)
        self.assertIn("libfrac:", out)


if __name__ == "__main__":
    TOOL = os.path.abspath(sys.argv.pop(1))
    ROOT = os.path.abspath(sys.argv.pop(1))
    unittest.main(verbosity=1)
