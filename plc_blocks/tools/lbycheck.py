#!/usr/bin/env python3
"""lbycheck: checks Automation Studio ANSI C library descriptors (ANSIC.lby)
so that the libraries import together.

usage: lbycheck.py LIBDIR...

For each library folder LIBDIR (the library's name is the folder's name):
  - ANSIC.lby parses and has SubType="ANSIC";
  - every <File> it lists exists (paths relative to LIBDIR) and is listed once;
  - every source under LIBDIR (.c, .h, .typ, .var, .fun, at any depth) is listed;
  - every <Dependency ObjectName="X"/> names one of the LIBDIRs given.
Errors go to stderr as "FILE:1: error: MESSAGE", exit status 1; success prints
one line per library.
"""
import os
import sys
import xml.etree.ElementTree as ET

SOURCE_EXT = (".c", ".h", ".typ", ".var", ".fun")


def local(tag):
    return tag.split("}")[-1]


def check(libdir, names):
    lby = os.path.join(libdir, "ANSIC.lby")
    errs = []

    def err(msg):
        errs.append("%s:1: error: %s" % (lby, msg))

    try:
        root = ET.parse(lby).getroot()
    except (OSError, ET.ParseError) as e:
        err("cannot read library descriptor: %s" % e)
        return errs, 0
    if local(root.tag) != "Library" or root.get("SubType") != "ANSIC":
        err("SubType is %r, expected \"ANSIC\" (an ANSI C library)" % root.get("SubType"))
    files = [f.text.strip() for f in root.iter() if local(f.tag) == "File" and f.text and f.text.strip()]
    if not files:
        err("lists no <File> entries")
    seen = set()
    for f in files:
        if f in seen:
            err("'%s' is listed twice" % f)
        seen.add(f)
        if not os.path.isfile(os.path.join(libdir, f)):
            err("'%s' is listed but does not exist" % f)
    for dirpath, _, fnames in os.walk(libdir):
        for fn in sorted(fnames):
            rel = os.path.relpath(os.path.join(dirpath, fn), libdir)
            if fn.endswith(SOURCE_EXT) and rel not in seen:
                err("'%s' is in the library but not in the descriptor" % rel)
    for d in root.iter():
        if local(d.tag) == "Dependency":
            dep = d.get("ObjectName")
            if dep not in names:
                err("dependency '%s' does not resolve: no library of that name among %s"
                    % (dep, ", ".join(sorted(names))))
    return errs, len(files)


def main(argv):
    if len(argv) < 2:
        sys.stderr.write("usage: lbycheck.py LIBDIR...\n")
        return 2
    dirs = [os.path.abspath(d) for d in argv[1:]]
    names = {os.path.basename(d) for d in dirs}
    status = 0
    for d in dirs:
        errs, n = check(d, names)
        for e in errs:
            sys.stderr.write(e + "\n")
        if errs:
            status = 1
        else:
            print("lbycheck: %s: %d files listed, all present, every source listed, dependencies resolve"
                  % (os.path.basename(d), n))
    return status


if __name__ == "__main__":
    sys.exit(main(sys.argv))
