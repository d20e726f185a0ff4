#!/usr/bin/env python3
"""plcgen: generate the C header of a B&R-style ANSI C library from its
IEC 61131-3 declarations (.typ, .var, .fun), which are the single source of
truth for every block interface (ARCHITECTURE.md, plc_blocks rules).

usage: plcgen.py [--config MACRO:ALIAS=TYPE]... [--plcopen OUT.xml] [--st PROG.st]... LIBRARY.lby OUT.h

--st PROG.st: parse a Structured Text program with the same parser and
type-check it against the library (stcheck.py: only declared pins, of the
right types); its interface goes into the PLCopen export, body external (ST).

--plcopen OUT.xml: also write the PLCopen TC6 XML v2.01 export of the
library's interface (plcopen.py): data types, function blocks, constants.

--config MACRO:ALIAS=TYPE: a build configuration of the library. With MACRO
defined, the C header declares the elementary alias ALIAS as TYPE instead of
its declared base type (FracCtrl: FRAC_REAL_FLOAT:FracReal=REAL, the
single-precision build of libfrac); the declarations stay those of the
default configuration.

The library descriptor (.lby, Automation Studio XML) lists the files of the
library. Every .typ/.var/.fun it lists is parsed; every FUNCTION_BLOCK must
have its body file <Name>.c listed in the descriptor and present on disk, and
every other .c file in the descriptor must either be a block body or carry
Description="Internal" (shared helpers of the bodies). Errors go to stderr as
"FILE:LINE: error: MESSAGE" with exit status 1.

Supported declarations (the subset the B&R library convention uses):
  .typ  TYPE ... END_TYPE with
          Name : STRUCT  field : Type; ...  END_STRUCT;
          Name : ( A := 0, B := 1 );            (enumeration)
          Name : BaseType;                       (alias)
          Name : ARRAY[0..n] OF LREAL;           (alias of an array: e.g. storage)
  A type whose documentation comment starts with  C: c_type "header.h";
  stands for that C type: the header includes "header.h" and checks at
  compile time (negative array size) that the C type fits the declared IEC
  data: an elementary alias has the C type's size and alignment; an array
  alias is at least as large and as aligned, and on the reference
  configuration (64-bit pointers, no --config macro defined) smaller than
  the C type plus one element, so the declaration is the least storage.
  For an array alias it also defines  Name_C(obj), the IEC storage as a
  pointer to the C type (the only way the bodies access it).
  Pragmas ({...}) are not IEC 61131-3 and are refused.
  .var  VAR CONSTANT  Name : Type := literal;  END_VAR
  .fun  FUNCTION_BLOCK Name  VAR_INPUT / VAR_OUTPUT / VAR  ...  END_VAR  END_FUNCTION_BLOCK
  Types: the IEC elementary types, declared names, ARRAY[lo..hi] OF Type
  (bounds are integers or declared constants), STRING[n], REFERENCE TO Type
  (a C pointer: caller-owned data such as parameter tables).
  Comments (* ... *) after a declaration become the C comment.
"""
import os
import re
import sys
import xml.etree.ElementTree as ET

IEC_TYPES = {"BOOL", "SINT", "USINT", "INT", "UINT", "DINT", "UDINT", "REAL", "LREAL"}
INTEGER_TYPES = {"SINT", "USINT", "INT", "UINT", "DINT", "UDINT"}
KEYWORDS = {"TYPE", "END_TYPE", "STRUCT", "END_STRUCT", "VAR", "VAR_INPUT", "VAR_OUTPUT",
            "VAR_IN_OUT", "END_VAR", "CONSTANT", "FUNCTION_BLOCK", "END_FUNCTION_BLOCK",
            "ARRAY", "OF", "STRING", "REFERENCE", "TO"}


class GenError(Exception):
    def __init__(self, path, line, msg):
        super().__init__("%s:%d: error: %s" % (path, line, msg))


TOKEN_RE = re.compile(r"""
    (?P<ws>[ \t\r\n]+)
  | (?P<comment>\(\*.*?\*\))
  | (?P<pragma>\{[^}]*\})
  | (?P<assign>:=)
  | (?P<range>\.\.)
  | (?P<real>[+-]?\d+\.\d+(?:[eE][+-]?\d+)?|[+-]?\d+[eE][+-]?\d+)
  | (?P<int>[+-]?(?:16\#[0-9A-Fa-f_]+|2\#[01_]+|\d[\d_]*))
  | (?P<ident>[A-Za-z_][A-Za-z0-9_]*)
  | (?P<op>=>|<=|>=|<>|[=<>+\-*/.#&])
  | (?P<punct>[:;(),\[\]])
""", re.S | re.X)


class Tok:
    def __init__(self, kind, text, line):
        self.kind, self.text, self.line = kind, text, line

    def __repr__(self):
        return "%s %r" % (self.kind, self.text)


def tokenize(path, text):
    toks, pos, line = [], 0, 1
    while pos < len(text):
        if text.startswith("(*", pos) and text.find("*)", pos + 2) < 0:
            raise GenError(path, line, "unterminated comment '(*'")
        m = TOKEN_RE.match(text, pos)
        if not m:
            raise GenError(path, line, "unexpected character %r" % text[pos])
        kind = m.lastgroup
        if kind != "ws":
            toks.append(Tok(kind, m.group(), line))
        line += m.group().count("\n")
        pos = m.end()
    toks.append(Tok("eof", "", line))
    return toks


def int_value(text):
    t = text.replace("_", "")
    sign = -1 if t.startswith("-") else 1
    t = t.lstrip("+-")
    if t.startswith("16#"):
        return sign * int(t[3:], 16)
    if t.startswith("2#"):
        return sign * int(t[2:], 2)
    return sign * int(t, 10)


class Parser:
    allow_fb_types = False  # function block instances as variables: programs only (stcheck.py)

    def __init__(self, path, text, lib):
        self.path, self.toks, self.i, self.lib = path, tokenize(path, text), 0, lib

    def peek(self, k=0):
        return self.toks[min(self.i + k, len(self.toks) - 1)]

    def err(self, msg, tok=None):
        return GenError(self.path, (tok or self.peek()).line, msg)

    def next(self):
        t = self.toks[self.i]
        if t.kind != "eof":
            self.i += 1
        return t

    def comment(self):
        """Collects comments (the documentation of the item just declared)."""
        parts = []
        while self.peek().kind == "comment":
            parts.append(self.next().text[2:-2].strip())
        return " ".join(p for p in parts if p)

    def expect(self, text, what=None):
        t = self.next()
        if t.text.upper() != text:
            raise self.err("expected '%s'%s, found %s" % (
                text, (" " + what) if what else "", repr(t.text) if t.text else "end of file"), t)
        return t

    def ident(self, what):
        t = self.next()
        if t.kind != "ident" or t.text.upper() in KEYWORDS:
            raise self.err("expected %s name, found %s" % (
                what, repr(t.text) if t.text else "end of file"), t)
        return t

    def bound(self):
        t = self.next()
        if t.kind == "int":
            return int_value(t.text)
        if t.kind == "ident" and t.text in self.lib.consts:
            c = self.lib.consts[t.text]
            if c["type"] not in INTEGER_TYPES:
                raise self.err("array bound '%s' is not an integer constant" % t.text, t)
            return int_value(c["value"])
        raise self.err("array bound must be an integer or a declared integer constant, found %r" % t.text, t)

    def type_ref(self):
        """Type := Name | ARRAY[lo..hi(, lo..hi)*] OF Name | STRING[n]. Returns (base, dims);
        self.lows holds the lower bounds of an array's dimensions."""
        t = self.peek()
        self.lows = []
        if t.text.upper() == "ARRAY":
            self.next()
            self.expect("[")
            dims, lows = [], []
            while True:
                lo_tok = self.peek()
                lo = self.bound()
                self.expect("..", "in array range")
                hi = self.bound()
                if hi < lo:
                    raise self.err("empty array range %d..%d" % (lo, hi), lo_tok)
                dims.append(hi - lo + 1)
                lows.append(lo)
                if self.peek().text == ",":
                    self.next()
                    continue
                break
            self.expect("]")
            self.expect("OF")
            base, inner = self.type_ref()
            if inner:
                raise self.err("nested ARRAY ... OF ARRAY is not supported; use ARRAY[a..b, c..d]")
            self.lows = lows
            return base, dims
        if t.text.upper() == "REFERENCE":
            self.next()
            self.expect("TO", "after REFERENCE")
            base, dims = self.type_ref()
            if dims:
                raise self.err("REFERENCE TO ARRAY is not supported; use REFERENCE TO the element type")
            return base + " *", []
        if t.text.upper() == "STRING":
            self.next()
            self.expect("[")
            n = self.bound()
            self.expect("]")
            return "plcstring", [n + 1]
        name = self.ident("type")
        if name.text in self.lib.fbs and self.allow_fb_types:
            return "FB:" + name.text, []
        if name.text not in IEC_TYPES and name.text not in self.lib.types:
            raise self.err("unknown type '%s' (not an IEC elementary type and not declared in a .typ file)"
                           % name.text, name)
        return name.text, []

    def member(self, section):
        """name : Type ; (*doc*)"""
        name = self.ident("variable")
        self.expect(":", "after '%s'" % name.text)
        base, dims = self.type_ref()
        if self.peek().kind == "assign":
            raise self.err("initial value for '%s' is not supported in %s (the runtime zero-initialises "
                           "instances)" % (name.text, section))
        self.expect(";", "after the declaration of '%s'" % name.text)
        lows = self.lows
        return {"name": name.text, "type": base, "dims": dims, "lows": lows, "doc": self.comment(),
                "line": name.line}

    # ---- .typ -------------------------------------------------------------
    def parse_typ(self):
        self.comment()
        while self.peek().kind != "eof":
            self.expect("TYPE")
            self.comment()
            while self.peek().text.upper() != "END_TYPE":
                self.type_decl()
            self.expect("END_TYPE")
            self.comment()

    def type_decl(self):
        name = self.ident("type")
        if name.text in self.lib.types or name.text in IEC_TYPES:
            raise self.err("type '%s' declared twice" % name.text, name)
        self.expect(":", "after type name '%s'" % name.text)
        doc = self.comment()
        t = self.peek()
        decl = {"name": name.text, "line": name.line, "doc": doc, "file": self.path}
        if t.text.upper() == "STRUCT":
            self.next()
            decl["kind"] = "struct"
            more = self.comment()
            decl["doc"] = (doc + " " + more).strip()
            # a struct may refer to itself only through types declared before it
            self.lib.types[name.text] = decl
            fields = []
            while self.peek().text.upper() != "END_STRUCT":
                if self.peek().kind == "eof":
                    raise self.err("STRUCT '%s' has no END_STRUCT" % name.text, name)
                fields.append(self.member("STRUCT"))
            self.next()
            if not fields:
                raise self.err("STRUCT '%s' has no fields" % name.text, name)
            check_unique(self, fields, "STRUCT " + name.text)
            decl["fields"] = fields
        elif t.text == "(":
            self.next()
            decl["kind"] = "enum"
            more = self.comment()
            decl["doc"] = (doc + " " + more).strip()
            values, nextval = [], 0
            while True:
                en = self.ident("enumerator")
                if self.peek().kind == "assign":
                    self.next()
                    v = self.next()
                    if v.kind != "int":
                        raise self.err("enumerator value must be an integer", v)
                    nextval = int_value(v.text)
                values.append({"name": en.text, "value": nextval, "doc": self.comment()})
                nextval += 1
                sep = self.next()
                if sep.text == ")":
                    break
                if sep.text != ",":
                    raise self.err("expected ',' or ')' in enumeration '%s'" % name.text, sep)
                self.comment()
            decl["values"] = values
            self.lib.types[name.text] = decl
        elif t.kind == "pragma":
            raise self.err("pragma %s in type '%s' is not IEC 61131-3: declare the data as IEC types (e.g. "
                           "ARRAY[0..n] OF LREAL) and name the C type in the comment as 'C: c_type \"header.h\";'"
                           % (t.text, name.text), t)
        else:
            base, dims = self.type_ref()
            decl.update(kind="alias", type=base, dims=dims, lows=self.lows)
            self.lib.types[name.text] = decl
        self.expect(";", "after the declaration of type '%s'" % name.text)
        more = self.comment()
        if more:
            decl["doc"] = (decl["doc"] + " " + more).strip()
        self.c_tag(decl, name)

    C_TAG_RE = re.compile(r'C:\s*([A-Za-z_][A-Za-z0-9_]*)\s+"([^"]+)"\s*;\s*')

    def c_tag(self, decl, name):
        """'C: c_type "header.h";' at the start of a type's comment: the C type it stands for."""
        m = self.C_TAG_RE.match(decl["doc"])
        if not m:
            if decl["doc"].startswith("C:"):
                raise self.err('malformed C type tag in the comment of \'%s\', expected C: c_type "header.h";'
                               % name.text, name)
            return
        elementary = decl["kind"] == "alias" and decl["type"] in IEC_TYPES
        if not (decl["kind"] == "alias" and (elementary or decl["dims"])):
            raise self.err("type '%s' names the C type %s but is not an alias of an elementary type or of "
                           "an array (only those can stand for a C type)" % (name.text, m.group(1)), name)
        decl.update(ctype=m.group(1), header=m.group(2), doc=decl["doc"][m.end():])

    # ---- .var -------------------------------------------------------------
    def parse_var(self):
        self.comment()
        while self.peek().kind != "eof":
            self.expect("VAR")
            self.expect("CONSTANT", "(a library exports constants only)")
            self.comment()
            while self.peek().text.upper() != "END_VAR":
                name = self.ident("constant")
                if name.text in self.lib.consts:
                    raise self.err("constant '%s' declared twice" % name.text, name)
                self.expect(":", "after '%s'" % name.text)
                ty = self.ident("type")
                if ty.text not in IEC_TYPES:
                    raise self.err("constant '%s' must have an elementary type" % name.text, ty)
                if self.peek().kind != "assign":
                    raise self.err("constant '%s' has no value (':= literal' missing)" % name.text)
                self.next()
                v = self.next()
                if ty.text in INTEGER_TYPES and v.kind != "int":
                    raise self.err("constant '%s' of type %s needs an integer literal, found %r"
                                   % (name.text, ty.text, v.text), v)
                if ty.text in ("REAL", "LREAL") and v.kind not in ("int", "real"):
                    raise self.err("constant '%s' needs a numeric literal" % name.text, v)
                if ty.text == "BOOL" and v.text.upper() not in ("TRUE", "FALSE"):
                    raise self.err("constant '%s' needs TRUE or FALSE" % name.text, v)
                if ty.text in INTEGER_TYPES:
                    check_range(self, v, ty.text, int_value(v.text))
                self.expect(";", "after the declaration of '%s'" % name.text)
                self.lib.consts[name.text] = {"name": name.text, "type": ty.text, "value": v.text,
                                              "doc": self.comment()}
            self.expect("END_VAR")
            self.comment()

    # ---- .fun -------------------------------------------------------------
    def parse_fun(self):
        self.comment()
        while self.peek().kind != "eof":
            kw = self.next()
            if kw.text.upper() != "FUNCTION_BLOCK":
                raise self.err("expected FUNCTION_BLOCK, found %r" % kw.text, kw)
            name = self.ident("function block")
            if name.text in self.lib.fbs or name.text in self.lib.types:
                raise self.err("'%s' declared twice" % name.text, name)
            fb = {"name": name.text, "doc": self.comment(), "line": name.line, "file": self.path,
                  "inputs": [], "outputs": [], "internal": []}
            while self.peek().text.upper() != "END_FUNCTION_BLOCK":
                sec = self.next()
                key = {"VAR_INPUT": "inputs", "VAR_OUTPUT": "outputs", "VAR": "internal"}.get(sec.text.upper())
                if key is None:
                    raise self.err("expected VAR_INPUT, VAR_OUTPUT, VAR or END_FUNCTION_BLOCK in '%s', found %s"
                                   % (name.text, repr(sec.text) if sec.text else "end of file"), sec)
                self.comment()
                while self.peek().text.upper() != "END_VAR":
                    if self.peek().text.upper() in KEYWORDS and self.peek(1).text == ":":
                        raise self.err("'%s' is a reserved word and cannot name a variable" % self.peek().text)
                    if self.peek().kind == "eof" or self.peek().text.upper() in KEYWORDS:
                        raise self.err("%s section of '%s' has no END_VAR" % (sec.text, name.text), sec)
                    fb[key].append(self.member(sec.text))
                self.next()
                self.comment()
            self.next()
            check_unique(self, fb["inputs"] + fb["outputs"] + fb["internal"], "FUNCTION_BLOCK " + name.text)
            self.lib.fbs[name.text] = fb
            self.comment()


def check_unique(parser, members, where):
    seen = {}
    for m in members:
        if m["name"] in seen:
            raise GenError(parser.path, m["line"], "'%s' declared twice in %s" % (m["name"], where))
        seen[m["name"]] = m


def check_range(parser, tok, ty, v):
    lo, hi = {"SINT": (-128, 127), "USINT": (0, 255), "INT": (-32768, 32767), "UINT": (0, 65535),
              "DINT": (-2 ** 31, 2 ** 31 - 1), "UDINT": (0, 2 ** 32 - 1)}[ty]
    if not lo <= v <= hi:
        raise GenError(parser.path, tok.line, "value %d out of range of %s" % (v, ty))


class Library:
    def __init__(self, name):
        self.name, self.types, self.consts, self.fbs = name, {}, {}, {}


def c_comment(doc):
    return (" /* %s */" % doc.replace("*/", "* /")) if doc else ""


def c_decl(base, name, dims):
    return "%s %s%s" % (base, name, "".join("[%d]" % d for d in dims))


def emit(lib, configs=()):
    guard = "%s_H_GENERATED" % lib.name.upper()
    out = ["/* %s.h: GENERATED by plc_blocks/tools/plcgen.py from %s.typ, %s.var, %s.fun." % (
        lib.name, lib.name, lib.name, lib.name),
        " * Do not edit: the IEC 61131-3 declarations are the single source of truth. */",
        "#ifndef %s" % guard, "#define %s" % guard, "", '#include "plctypes.h"']
    headers = []
    for t in lib.types.values():
        if "ctype" in t and t["header"] not in headers:
            headers.append(t["header"])
    if headers:
        out.append("#include <stddef.h>")
    out += ['#include "%s"' % h for h in headers]
    out += ["", "#ifdef __cplusplus", 'extern "C" {', "#endif", ""]
    if lib.consts:
        out.append("/* Constants (%s.var) */" % lib.name)
        for c in lib.consts.values():
            v = c["value"]
            if c["type"] in INTEGER_TYPES:
                n = int_value(v)
                v = ("%dU" % n) if c["type"].startswith("U") else ("(%d)" % n if n < 0 else "%d" % n)
            elif c["type"] == "BOOL":
                v = "1" if v.upper() == "TRUE" else "0"
            elif c["type"] == "REAL":
                v = "%sf" % (v if ("." in v or "e" in v.lower()) else v + ".0")
            out.append("#define %s ((%s)%s)%s" % (c["name"], c["type"], v, c_comment(c["doc"])))
        out.append("")
    out.append("/* Data types (%s.typ) */" % lib.name)
    for t in lib.types.values():
        conf = [c for c in configs if c[1] == t["name"]]
        if t["kind"] == "alias" and conf:
            for k, (macro, _, ty) in enumerate(conf):
                out.append("#%s defined(%s)" % ("if" if k == 0 else "elif", macro))
                out.append("typedef %s %s;%s" % (ty, t["name"], c_comment("configuration " + macro)))
            out.append("#else")
            out.append("typedef %s;%s" % (c_decl(t["type"], t["name"], t["dims"]), c_comment(t["doc"])))
            out.append("#endif")
        elif t["kind"] == "alias":
            out.append("typedef %s;%s" % (c_decl(t["type"], t["name"], t["dims"]), c_comment(t["doc"])))
        elif t["kind"] == "enum":
            out.append("typedef enum %s {%s" % (t["name"], c_comment(t["doc"])))
            for k, v in enumerate(t["values"]):
                sep = "," if k + 1 < len(t["values"]) else ""
                out.append("    %s = %d%s%s" % (v["name"], v["value"], sep, c_comment(v["doc"])))
            out.append("} %s;" % t["name"])
        else:
            out.append("typedef struct %s {%s" % (t["name"], c_comment(t["doc"])))
            for f in t["fields"]:
                out.append("    %s;%s" % (c_decl(f["type"], f["name"], f["dims"]), c_comment(f["doc"])))
            out.append("} %s;" % t["name"])
        out.append("")
    out += emit_layout_checks(lib, configs)
    out.append("/* Function blocks (%s.fun) */" % lib.name)
    for fb in lib.fbs.values():
        out.append("/* %s%s */" % (fb["name"], (": " + fb["doc"]) if fb["doc"] else ""))
        out.append("typedef struct %s {" % fb["name"])
        for key, title in (("inputs", "VAR_INPUT"), ("outputs", "VAR_OUTPUT"), ("internal", "VAR")):
            if fb[key]:
                out.append("    /* %s */" % title)
            for f in fb[key]:
                out.append("    %s;%s" % (c_decl(f["type"], f["name"], f["dims"]), c_comment(f["doc"])))
        out.append("} %s_typ;" % fb["name"])
        out.append("void %s(struct %s* inst);" % (fb["name"], fb["name"]))
        out.append("")
    out += ["#ifdef __cplusplus", "}", "#endif", "", "#endif /* %s */" % guard, ""]
    return "\n".join(out)


def emit_layout_checks(lib, configs):
    """Compile-time proof that each type naming a C type holds it (negative array size)."""
    tagged = [t for t in lib.types.values() if "ctype" in t]
    if not tagged:
        return []
    out = ["/* Layout: each IEC type below stands for a C type; a negative array size stops the build",
           "   when the C type does not fit (size, alignment; least storage on the reference",
           "   configuration: 64-bit pointers, no configuration macro). */"]
    tight, ref = [], " && ".join("!defined(%s)" % m for m in sorted({c[0] for c in configs})) or "1"
    for t in tagged:
        n, c = t["name"], t["ctype"]
        out.append("struct %s_align_c { char c; %s x; };" % (n, c))
        out.append("struct %s_align_iec { char c; %s x; };" % (n, n))
        al_c, al_i = "offsetof(struct %s_align_c, x)" % n, "offsetof(struct %s_align_iec, x)" % n
        if t["dims"]:
            out.append("#define %s_C(obj) ((%s *)(void *)(obj)) /* the storage as the C object */" % (n, c))
            out.append("typedef char %s_holds_%s[(sizeof(%s) <= sizeof(%s)) ? 1 : -1];" % (n, c, c, n))
            out.append("typedef char %s_aligned_for_%s[(%s <= %s) ? 1 : -1];" % (n, c, al_c, al_i))
            tight.append("typedef char %s_least_for_%s[(sizeof(void *) != 8 || sizeof(%s) - sizeof(%s) < "
                         "sizeof(%s)) ? 1 : -1];" % (n, c, n, c, t["type"]))
        else:
            out.append("typedef char %s_size_of_%s[(sizeof(%s) == sizeof(%s)) ? 1 : -1];" % (n, c, c, n))
            out.append("typedef char %s_align_of_%s[(%s == %s) ? 1 : -1];" % (n, c, al_c, al_i))
    out += ["#if %s" % ref] + tight + ["#endif", ""]
    return out


def read_lby(path):
    try:
        root = ET.parse(path).getroot()
    except (OSError, ET.ParseError) as e:
        raise GenError(path, 1, "cannot read library descriptor: %s" % e)
    files = [(f.text.strip(), f.get("Description", "")) for f in root.iter()
             if f.tag.split("}")[-1] == "File" and f.text]
    if not files:
        raise GenError(path, 1, "library descriptor lists no <File> entries")
    return files


def generate(lby):
    libdir = os.path.dirname(os.path.abspath(lby))
    entries = read_lby(lby)
    files = [f for f, _ in entries]
    lib = Library(os.path.basename(libdir))
    lib.version = ET.parse(lby).getroot().get("Version", "0")
    order = {".var": 0, ".typ": 1, ".fun": 2}
    decl_files = sorted((f for f in files if os.path.splitext(f)[1] in order),
                        key=lambda f: order[os.path.splitext(f)[1]])
    for f in files:
        if not os.path.isfile(os.path.join(libdir, f)):
            raise GenError(lby, 1, "file '%s' listed in the descriptor does not exist" % f)
    for f in decl_files:
        path = os.path.join(libdir, f)
        with open(path, encoding="utf-8") as fh:
            p = Parser(path, fh.read(), lib)
        {".typ": p.parse_typ, ".var": p.parse_var, ".fun": p.parse_fun}[os.path.splitext(f)[1]]()
    bodies = {os.path.splitext(f)[0] for f, d in entries if f.endswith(".c") and d != "Internal"}
    for fb in lib.fbs.values():
        if fb["name"] not in bodies:
            raise GenError(fb["file"], fb["line"], "function block '%s' has no body %s.c in the library "
                           "descriptor" % (fb["name"], fb["name"]))
    listed = set(files)
    for f in sorted(os.listdir(libdir)):
        if os.path.splitext(f)[1] in (".c", ".h", ".fun", ".typ", ".var") and f not in listed:
            raise GenError(lby, 1, "'%s' is in the library folder but not in the descriptor" % f)
    for b in sorted(bodies - set(lib.fbs)):
        raise GenError(lby, 1, "body '%s.c' has no FUNCTION_BLOCK declaration in the .fun file" % b)
    return lib


USAGE = "usage: plcgen.py [--config MACRO:ALIAS=TYPE]... [--plcopen OUT.xml] [--st PROG.st]... LIBRARY.lby OUT.h\n"


def write_if_changed(path, data):
    """Writes data (bytes) through a temporary file, so a failure leaves no half-written output."""
    if os.path.exists(path):
        with open(path, "rb") as fh:
            if fh.read() == data:
                return
    tmp = path + ".tmp"
    with open(tmp, "wb") as fh:
        fh.write(data)
    os.replace(tmp, path)


def parse_configs(lib, specs):
    configs = []
    for spec in specs:
        m = re.fullmatch(r"([A-Za-z_]\w*):([A-Za-z_]\w*)=([A-Za-z_]\w*)", spec)
        if not m:
            raise GenError("--config", 1, "'%s' is not MACRO:ALIAS=TYPE" % spec)
        t = lib.types.get(m.group(2))
        if t is None or t["kind"] != "alias" or t["type"] not in IEC_TYPES:
            raise GenError("--config", 1, "'%s' is not a declared alias of an elementary type" % m.group(2))
        if m.group(3) not in IEC_TYPES:
            raise GenError("--config", 1, "'%s' is not an IEC elementary type (allowed: %s)"
                           % (m.group(3), ", ".join(sorted(IEC_TYPES))))
        configs.append(m.groups())
    return configs


def main(argv):
    args, specs, plcopen_out, st_files = argv[1:], [], None, []
    while len(args) >= 2 and args[0] in ("--config", "--plcopen", "--st"):
        if args[0] == "--config":
            specs.append(args[1])
        elif args[0] == "--st":
            st_files.append(args[1])
        else:
            plcopen_out = args[1]
        args = args[2:]
    if len(args) != 2 or args[0].startswith("--"):
        sys.stderr.write(USAGE)
        return 2
    argv = [argv[0]] + args
    try:
        lib = generate(argv[1])
        configs = parse_configs(lib, specs)
        import stcheck
        programs = stcheck.parse_programs(lib, st_files)
    except GenError as e:
        sys.stderr.write("%s\n" % e)
        return 1
    write_if_changed(argv[2], emit(lib, configs).encode("utf-8"))
    if plcopen_out:
        import plcopen
        for prog in programs:
            prog.update(language="ST", body=os.path.basename(prog["file"]))
        write_if_changed(plcopen_out, plcopen.export(lib, lib.version, programs))
    return 0


if __name__ == "__main__":
    sys.modules.setdefault("plcgen", sys.modules[__name__])  # stcheck/plcopen share this module's classes
    sys.exit(main(sys.argv))
