"""stcheck: Structured Text programs parsed and type-checked against a
library's declarations, by plcgen.py's own parser (the same tokenizer, type
and declaration rules) extended with the ST statements the usage examples
use (IEC 61131-3 3rd ed. 7.3):

  PROGRAM Name  VAR_INPUT / VAR_OUTPUT / VAR [CONSTANT] ... END_VAR
                statements  END_PROGRAM
  statements:   v := expr;   inst(Pin := expr, Pin => v, ...);
                IF expr THEN ... {ELSIF expr THEN ...} [ELSE ...] END_IF;   RETURN;
  expressions:  OR XOR AND & = <> < > <= >= + - * / MOD NOT, unary -,
                literals, TRUE/FALSE, Enum#value, v.member, v[i, j],
                REF(v), SIZEOF(v), ABS, MIN, MAX, LIMIT, X_TO_Y conversions.

Every call of a function block may name only its declared VAR_INPUT pins
(:=) and VAR_OUTPUT pins (=>), each with a value of the pin's type; a member
access on an instance reaches only its pins (never its VAR internals). Types
are compatible when equal, or by the implicit widening conversions of
IEC 61131-3 (2013) Fig. 11 (e.g. REAL -> LREAL, UINT -> UDINT); narrowing
needs an explicit X_TO_Y. Errors: GenError, "FILE:LINE: error: MESSAGE"."""
import json

from plcgen import GenError, IEC_TYPES, INTEGER_TYPES, KEYWORDS, Parser

ST_KEYWORDS = {"PROGRAM", "END_PROGRAM", "IF", "THEN", "ELSIF", "ELSE", "END_IF", "RETURN", "AND", "OR",
               "XOR", "NOT", "MOD", "TRUE", "FALSE"}
REALS = ("REAL", "LREAL")
WIDEN = {"SINT": {"INT", "DINT", "REAL", "LREAL"}, "INT": {"DINT", "REAL", "LREAL"}, "DINT": {"LREAL"},
         "USINT": {"UINT", "UDINT", "INT", "DINT", "REAL", "LREAL"}, "UINT": {"UDINT", "DINT", "REAL", "LREAL"},
         "UDINT": {"LREAL"}, "REAL": {"LREAL"}}


class StParser(Parser):
    allow_fb_types = True

    def __init__(self, path, text, lib):
        super().__init__(path, text, lib)
        self.vars = {}
        self.calls = []  # (instance, function block) in the order of the program text

    # ---- types ------------------------------------------------------------
    def resolve(self, base, dims=()):
        """Canonical type text: elementary, 'ARRAY[d,..]:T', 'REF:T', 'STRING', 'FB:Name', or a named type."""
        if dims and base == "plcstring":
            return "STRING"
        if dims:
            return "ARRAY%s:%s" % (list(dims), self.resolve(base))
        if base.endswith(" *"):
            return "REF:" + self.resolve(base[:-2])
        t = self.lib.types.get(base)
        if t and t["kind"] == "alias":
            return self.resolve(t["type"], t["dims"])
        return base

    def accepts(self, target, source):
        if target == source:
            return True
        if source == "ANY_INT":
            return target in INTEGER_TYPES
        if source == "ANY_REAL":
            return target in REALS
        return target in WIDEN.get(source, ())

    def need(self, target, source, what, tok):
        if not self.accepts(target, source):
            raise self.err("%s: %s expected, found %s" % (what, shown(target), shown(source)), tok)

    # ---- program ----------------------------------------------------------
    def parse_program(self):
        self.comment()
        self.expect("PROGRAM")
        name = self.ident("program")
        prog = {"name": name.text, "doc": self.comment(), "line": name.line, "file": self.path,
                "inputs": [], "outputs": [], "internal": []}
        while self.peek().text.upper() in ("VAR", "VAR_INPUT", "VAR_OUTPUT"):
            sec = self.next()
            constant = self.peek().text.upper() == "CONSTANT"
            if constant:
                self.next()
            key = {"VAR_INPUT": "inputs", "VAR_OUTPUT": "outputs", "VAR": "internal"}[sec.text.upper()]
            self.comment()
            while self.peek().text.upper() != "END_VAR":
                if self.peek().kind == "eof" or self.peek().text.upper() in KEYWORDS:
                    raise self.err("%s section of '%s' has no END_VAR" % (sec.text, name.text), sec)
                prog[key].append(self.variable(constant))
            self.next()
            self.comment()
        # comments in the body document the code, not an item: the statements do not see them
        self.toks = self.toks[:self.i] + [t for t in self.toks[self.i:] if t.kind != "comment"]
        self.statements({"END_PROGRAM"})
        self.expect("END_PROGRAM")
        if self.peek().kind != "eof":
            raise self.err("text after END_PROGRAM")
        prog["calls"] = self.calls
        for key in ("inputs", "outputs", "internal"):
            for m in prog[key]:
                if m["type"].startswith("FB:"):
                    m["type"] = m["type"][3:]
        return prog

    def variable(self, constant):
        name = self.ident("variable")
        if name.text in self.vars or name.text in self.lib.consts:
            raise self.err("'%s' declared twice" % name.text, name)
        self.expect(":", "after '%s'" % name.text)
        base, dims = self.type_ref()
        lows = self.lows
        ty = base[3:] if base.startswith("FB:") else self.resolve(base, dims)
        if self.peek().kind == "assign":
            tok = self.next()
            self.need(ty, self.expr(), "initial value of '%s'" % name.text, tok)
        elif constant:
            raise self.err("constant '%s' has no value (':= literal' missing)" % name.text, name)
        self.expect(";", "after the declaration of '%s'" % name.text)
        self.vars[name.text] = {"type": ty, "fb": base.startswith("FB:"), "constant": constant}
        return {"name": name.text, "type": base, "dims": dims, "lows": lows, "doc": self.comment(),
                "line": name.line}

    # ---- statements -------------------------------------------------------
    def statements(self, ends):
        while self.peek().text.upper() not in ends:
            if self.peek().kind == "eof":
                raise self.err("expected %s, found end of file" % " or ".join(sorted(ends)))
            self.statement()

    def statement(self):
        t = self.peek()
        kw = t.text.upper()
        if kw == "IF":
            self.next()
            while True:
                self.need("BOOL", self.expr(), "condition", t)
                self.expect("THEN")
                self.statements({"ELSIF", "ELSE", "END_IF"})
                t = self.next()
                if t.text.upper() != "ELSIF":
                    break
            if t.text.upper() == "ELSE":
                self.statements({"END_IF"})
                self.expect("END_IF")
            self.expect(";", "after END_IF")
            return
        if kw == "RETURN":
            self.next()
            self.expect(";", "after RETURN")
            return
        if t.kind != "ident" or kw in ST_KEYWORDS or kw in KEYWORDS:
            raise self.err("expected a statement, found %r" % t.text, t)
        v = self.vars.get(t.text)
        if v and v["fb"] and self.peek(1).text == "(":
            self.call(self.next(), v["type"])
        else:
            lhs_tok = t
            lhs = self.designator(assign=True)
            tok = self.expect(":=", "in the assignment to '%s'" % lhs_tok.text)
            self.need(lhs, self.expr(), "assignment to '%s'" % lhs_tok.text, tok)
        self.expect(";", "after the statement")

    def call(self, inst, fbname):
        fb = self.lib.fbs[fbname]
        self.calls.append((inst.text, fbname))
        self.expect("(")
        seen = set()
        while self.peek().text != ")":
            pin = self.ident("pin")
            if pin.text in seen:
                raise self.err("pin '%s' of %s given twice" % (pin.text, inst.text), pin)
            seen.add(pin.text)
            op = self.next()
            if op.kind == "assign":
                decl = {m["name"]: m for m in fb["inputs"]}.get(pin.text)
                if decl is None:
                    raise self.err("'%s' is not an input of %s (%s is %s; inputs: %s)" % (
                        pin.text, fbname, inst.text, fbname, ", ".join(m["name"] for m in fb["inputs"])), pin)
                self.need(self.resolve(decl["type"], decl["dims"]), self.expr(),
                          "input %s.%s" % (inst.text, pin.text), pin)
            elif op.text == "=>":
                decl = {m["name"]: m for m in fb["outputs"]}.get(pin.text)
                if decl is None:
                    raise self.err("'%s' is not an output of %s (outputs: %s)" % (
                        pin.text, fbname, ", ".join(m["name"] for m in fb["outputs"])), pin)
                target = self.designator(assign=True)
                self.need(target, self.resolve(decl["type"], decl["dims"]), "output %s.%s" % (inst.text, pin.text),
                          pin)
            else:
                raise self.err("expected ':=' or '=>' after pin '%s'" % pin.text, op)
            if self.peek().text == ",":
                self.next()
        self.next()

    # ---- expressions ------------------------------------------------------
    def designator(self, assign=False):
        t = self.ident("variable")
        v = self.vars.get(t.text)
        if v is None:
            if t.text in self.lib.consts and not assign:
                return self.lib.consts[t.text]["type"]
            raise self.err("'%s' is not a declared variable" % t.text, t)
        if assign and v["constant"]:
            raise self.err("'%s' is a constant" % t.text, t)
        ty = v["type"]
        fb = ty if v["fb"] else None
        while self.peek().text in (".", "["):
            if self.next().text == ".":
                m = self.ident("member")
                if fb:
                    pins = {x["name"]: x for x in self.lib.fbs[fb]["inputs"] + self.lib.fbs[fb]["outputs"]}
                    if m.text not in pins:
                        raise self.err("'%s' is not a pin of %s" % (m.text, fb), m)
                    if assign and m.text in {x["name"] for x in self.lib.fbs[fb]["outputs"]}:
                        raise self.err("output %s.%s cannot be assigned" % (t.text, m.text), m)
                    ty, fb = self.resolve(pins[m.text]["type"], pins[m.text]["dims"]), None
                else:
                    st = self.lib.types.get(ty)
                    if not st or st["kind"] != "struct":
                        raise self.err("'%s' has type %s, which has no members" % (t.text, shown(ty)), m)
                    f = {x["name"]: x for x in st["fields"]}.get(m.text)
                    if f is None:
                        raise self.err("'%s' is not a member of %s" % (m.text, ty), m)
                    ty = self.resolve(f["type"], f["dims"])
            else:
                if not ty.startswith("ARRAY"):
                    raise self.err("'%s' is not an array" % t.text, t)
                dims, elem = ty[5:].split(":", 1)
                n = len(json.loads(dims))
                for k in range(n):
                    tok = self.peek()
                    idx = self.expr()
                    if idx not in INTEGER_TYPES and idx != "ANY_INT":
                        raise self.err("array index must be an integer, found %s" % shown(idx), tok)
                    if k + 1 < n:
                        self.expect(",", "between the indices of '%s'" % t.text)
                self.expect("]")
                ty = elem
        if fb:
            raise self.err("function block instance '%s' used as a value" % t.text, t)
        return ty

    def expr(self):
        return self.binary(0)

    LEVELS = (("OR",), ("XOR",), ("AND", "&"), ("=", "<>", "<", ">", "<=", ">="), ("+", "-"), ("*", "/", "MOD"))

    def binary(self, level):
        if level == len(self.LEVELS):
            return self.unary()
        left = self.binary(level + 1)
        while self.peek().text.upper() in self.LEVELS[level]:
            op = self.next()
            right = self.binary(level + 1)
            if level < 3:
                self.need("BOOL", left, "operand of %s" % op.text, op)
                self.need("BOOL", right, "operand of %s" % op.text, op)
                left = "BOOL"
            elif level == 3:
                if not (self.accepts(left, right) or self.accepts(right, left)):
                    raise self.err("cannot compare %s with %s" % (shown(left), shown(right)), op)
                left = "BOOL"
            else:
                left = self.numeric(left, right, op)
        return left

    def numeric(self, a, b, op):
        for x in (a, b):
            if x not in INTEGER_TYPES and x not in REALS and x not in ("ANY_INT", "ANY_REAL"):
                raise self.err("operand of '%s' is %s, not a number" % (op.text, shown(x)), op)
        if self.accepts(a, b):
            return a if not a.startswith("ANY") or b.startswith("ANY") else b
        if self.accepts(b, a):
            return b
        raise self.err("operands of '%s' have types %s and %s (convert one with X_TO_Y)" % (op.text, shown(a), shown(b)), op)

    def unary(self):
        t = self.peek()
        if t.text.upper() == "NOT":
            self.next()
            self.need("BOOL", self.unary(), "operand of NOT", t)
            return "BOOL"
        if t.text == "-":
            self.next()
            ty = self.unary()
            self.numeric(ty, ty, t)
            return ty
        return self.primary()

    def primary(self):
        t = self.peek()
        if t.kind == "int":
            self.next()
            return "ANY_INT"
        if t.kind == "real":
            self.next()
            return "ANY_REAL"
        if t.text.upper() in ("TRUE", "FALSE"):
            self.next()
            return "BOOL"
        if t.text == "(":
            self.next()
            ty = self.expr()
            self.expect(")")
            return ty
        if t.kind != "ident":
            raise self.err("expected an expression, found %r" % t.text, t)
        if self.peek(1).text == "#":
            enum = self.lib.types.get(t.text)
            self.next()
            self.next()
            v = self.ident("enumerator")
            if not enum or enum["kind"] != "enum" or v.text not in [x["name"] for x in enum["values"]]:
                raise self.err("'%s#%s' is not a declared enumerator" % (t.text, v.text), v)
            return t.text
        for e in self.lib.types.values():
            if e["kind"] == "enum" and t.text in [x["name"] for x in e["values"]]:
                self.next()
                return e["name"]
        if self.peek(1).text == "(" and t.text not in self.vars:
            return self.function()
        return self.designator()

    def function(self):
        name = self.next()
        fn = name.text.upper()
        self.expect("(")
        args = []
        if fn in ("REF", "SIZEOF"):
            args.append(self.designator())
        else:
            while self.peek().text != ")":
                args.append(self.expr())
                if self.peek().text == ",":
                    self.next()
        self.expect(")")
        if fn == "REF":
            return "REF:" + args[0]
        if fn == "SIZEOF":
            return "UDINT"
        if "_TO_" in fn:
            src, dst = fn.split("_TO_", 1)
            if src in IEC_TYPES and dst in IEC_TYPES and len(args) == 1:
                self.need(src, args[0], "argument of %s" % name.text, name)
                return dst
        if fn in ("ABS", "MIN", "MAX", "LIMIT") and args:
            ty = args[0]
            for a in args[1:]:
                ty = self.numeric(ty, a, name)
            if fn == "ABS" and len(args) != 1 or fn == "LIMIT" and len(args) != 3:
                raise self.err("%s takes %d arguments" % (fn, 1 if fn == "ABS" else 3), name)
            return ty
        raise self.err("'%s' is not a declared variable or a supported function" % name.text, name)


def shown(ty):
    if ty.startswith("ARRAY"):
        dims, elem = ty[5:].split(":", 1)
        return "ARRAY[%s] OF %s" % (", ".join("0..%d" % (d - 1) for d in json.loads(dims)), shown(elem))
    if ty.startswith("REF:"):
        return "REF_TO " + shown(ty[4:])
    return {"ANY_INT": "an integer literal", "ANY_REAL": "a real literal"}.get(ty, ty)


def parse_programs(lib, paths):
    """Parses and type-checks every ST file; returns the programs (name, sections, doc, file)."""
    progs = []
    for path in paths:
        try:
            with open(path, encoding="utf-8") as fh:
                text = fh.read()
        except OSError as e:
            raise GenError(path, 1, "cannot read: %s" % e)
        p = StParser(path, text, lib)
        prog = p.parse_program()
        if any(prog["name"] == q["name"] for q in progs) or prog["name"] in lib.fbs:
            raise GenError(path, prog["line"], "program '%s' declared twice" % prog["name"])
        progs.append(prog)
    return progs
