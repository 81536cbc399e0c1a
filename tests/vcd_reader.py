"""A small reader of value change dumps (IEEE 1364 VCD) for tests/test_vcd.sh: the variables by
scope, each variable's changes in time order, the last timestamp, and integrals over windows."""
import re


class Vcd:
    def __init__(self, path):
        self.timescale = None
        self.vars = {}      # id -> (scope path "a.b", name, width)
        self.changes = {}   # id -> [(time, value)]; value an int, or None for x
        self.times = []     # every timestamp, in file order
        self.comment = ""
        self._parse(open(path).read().split())

    def _parse(self, tok):
        scope, i, t = [], 0, None
        while i < len(tok):
            w = tok[i]
            if w in ("$scope", "$var", "$timescale", "$comment", "$version", "$date", "$enddefinitions", "$upscope"):
                j = tok.index("$end", i)
                body = tok[i + 1:j]
                if w == "$scope":
                    scope.append(body[1])
                elif w == "$upscope":
                    scope.pop()
                elif w == "$var":
                    self.vars[body[2]] = (".".join(scope), body[3], int(body[1]))
                    self.changes[body[2]] = []
                elif w == "$timescale":
                    self.timescale = "".join(body)
                elif w == "$comment":
                    self.comment = " ".join(body)
                i = j + 1
                continue
            if w in ("$dumpvars", "$end"):
                i += 1
                continue
            if w.startswith("#"):
                t = int(w[1:])
                assert not self.times or t > self.times[-1], "timestamps must increase: %d after %d" % (t, self.times[-1])
                self.times.append(t)
            elif w[0] in "bB":
                self._change(tok[i + 1], t, w[1:])
                i += 1
            elif w[0] in "01xXzZ":
                self._change(w[1:], t, w[0])
            else:
                raise ValueError("bad token %r" % w)
            i += 1

    def _change(self, ident, t, bits):
        assert t is not None and ident in self.changes, (ident, t)
        v = None if re.search("[xXzZ]", bits) else int(bits, 2)
        self.changes[ident].append((t, v))

    def find(self, scope, name):
        """The id of variable name in scope (e.g. "dynrtc.pipe0.trav", "busy")."""
        for ident, (s, n, _) in self.vars.items():
            if s == scope and n == name:
                return ident
        raise KeyError(scope + "." + name)

    def integral(self, ident, t0, t1):
        """Sum over [t0, t1) of the value (x counts 0), in time units."""
        total, ch = 0, self.changes[ident]
        for k, (t, v) in enumerate(ch):
            nxt = ch[k + 1][0] if k + 1 < len(ch) else self.times[-1]
            a, b = max(t, t0), min(nxt, t1)
            if b > a and v:
                total += v * (b - a)
        return total
