#!/usr/bin/python3
"""Checks that the sources of each unity-built target can share a translation unit.

A CMake unity build (ALPHAFLEX_UNITY_BUILD, docs/testing.md "Time of the suite") compiles batches
of a target's sources as one translation unit: what one source declares for itself alone is then
seen by the next sources of its batch, and an anonymous namespace is one namespace for the whole
batch. A name that two sources both define for themselves is then a compile error or, worse, one
more overload that silently changes which function a call picks. For each target this script
lists the names every source defines for itself at namespace scope — in an anonymous namespace,
`static`, or a namespace-scope constant (internal linkage), and the types, aliases and
using-declarations a source puts in a namespace — and fails when

  1. two sources of the target define the same name (an identical using-declaration, alias or
     namespace alias is a harmless redeclaration);
  2. a source defines for itself a name that the target's shared headers (the project's include/,
     and the target's own headers) declare at namespace scope: in a batch it would join or hide
     the header's name for the next sources too;
  3. a source has a using-directive (`using namespace X;`) at namespace scope: it stays in force
     for the rest of the batch and brings X's names into the next sources' lookup;
  4. a source leaves a macro defined (no #undef) whose name another source of the target uses;
  5. a GoogleTest test (Suite, Name) is defined twice, or one suite is used both with TEST and
     with TEST_F/TEST_P (GoogleTest refuses that at run time).

Sources that a CMakeLists.txt marks SKIP_UNITY_BUILD_INCLUSION are compiled alone and are not
checked (the library's list in CMakeLists.txt is read, not copied).

This is a careful lexer and a scope-tracking reader of namespace-scope declarations, not a
compiler: it skips comments, string and character literals (raw strings included) and the bodies
of functions and classes, and reads the declarations between them. `--list` prints what it read.

Usage: /usr/bin/python3 scripts/check_unity_names.py [--source-dir DIR] [--list]
Exit status 0 when every target is unity-safe, 1 otherwise (one line per problem, naming the
files, lines and the name). Run by ctest as `unity_names` (tests/CMakeLists.txt).
"""
import argparse
import glob
import os
import re
import sys
from collections import defaultdict

# The unity-built targets as CMakeLists.txt and tests/CMakeLists.txt make them: name, the
# CMakeLists.txt whose SKIP_UNITY_BUILD_INCLUSION list applies, the sources (globs relative to the
# source directory), the sources left out of the target, and the target's shared headers.
TARGETS = [
    {
        "name": "alphaflex",
        "cmakelists": "CMakeLists.txt",
        "sources": ["src/**/*.cpp"],
        # the executable's main and the gmsh module (CMakeLists.txt: their own targets, not unity)
        "excluded": ["src/app/main.cpp", "src/mesh/gmsh_reader.cpp", "src/mesh/msh_check.cpp"],
        "headers": ["include/**/*.hpp", "src/**/*.hpp"],
    },
    {
        "name": "unit_tests",
        "cmakelists": "tests/CMakeLists.txt",
        "sources": ["tests/unit/*.cpp"],
        "excluded": [],
        "headers": ["include/**/*.hpp", "tests/unit/*.hpp"],
    },
]

TEST_MACROS = {"TEST", "TEST_F", "TEST_P", "TYPED_TEST", "TYPED_TEST_P"}
STRING_PREFIXES = {"L", "u", "U", "u8", "R", "LR", "uR", "UR", "u8R"}
PUNCT2 = {"::", "->", "&&", "||", "==", "!=", "<=", ">=", "+=", "-=", "*=", "/=", "++", "--"}
KEYWORDS = {
    "const", "constexpr", "static", "inline", "extern", "volatile", "mutable", "thread_local", "unsigned",
    "signed", "int", "long", "short", "char", "double", "float", "bool", "void", "auto", "struct", "class",
    "enum", "union", "typename", "template", "operator", "noexcept", "override", "final", "decltype",
    "consteval", "constinit", "sizeof", "nullptr", "true", "false", "this", "new", "delete", "return",
    "LIT", "{}",
}
# Redeclaring these to the same thing is allowed, so the same declaration in two sources is no clash.
REDECLARABLE = {"using-declaration", "alias", "typedef", "namespace alias"}
IDENT = re.compile(r"[A-Za-z_][A-Za-z0-9_]*$")


def is_ident(t):
    return IDENT.match(t) is not None and t not in KEYWORDS


class Token:
    __slots__ = ("text", "line")

    def __init__(self, text, line):
        self.text = text
        self.line = line

    def __repr__(self):
        return self.text


# ------------------------------------------------------------------------------------------ lexer

def lex(text):
    """Tokens (every literal as "LIT") and preprocessor directives [(line, text)]."""
    tokens, directives = [], []
    i, n, line = 0, len(text), 1
    line_start = True
    ident = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")
    number = re.compile(r"\.?[0-9](?:[eEpP][+-]|[0-9A-Za-z_.']|)*")

    def skip_quoted(j, quote):
        nonlocal line
        j += 1
        while j < n and text[j] != quote and text[j] != "\n":
            if text[j] == "\\":
                if j + 1 < n and text[j + 1] == "\n":
                    line += 1
                j += 1
            j += 1
        return j + 1

    def skip_comment(j):
        """j at "/*" or "//": the index after the comment."""
        nonlocal line
        if text.startswith("/*", j):
            end = text.find("*/", j + 2)
            end = n if end < 0 else end + 2
            line += text.count("\n", j, end)
            return end
        while j < n and text[j] != "\n":
            if text[j] == "\\" and j + 1 < n and text[j + 1] == "\n":
                line += 1
                j += 1
            j += 1
        return j

    while i < n:
        c = text[i]
        if c == "\n":
            line += 1
            i += 1
            line_start = True
        elif c in " \t\r\f\v":
            i += 1
        elif c == "\\" and i + 1 < n and text[i + 1] == "\n":
            line += 1
            i += 2
        elif text.startswith("//", i) or text.startswith("/*", i):
            i = skip_comment(i)
        elif c == "#" and line_start:
            start_line, parts, j = line, [], i + 1
            while j < n and text[j] != "\n":
                if text[j] == "\\" and j + 1 < n and text[j + 1] == "\n":
                    line += 1
                    j += 2
                    parts.append(" ")
                elif text.startswith("//", j) or text.startswith("/*", j):
                    j = skip_comment(j)
                    parts.append(" ")
                else:
                    parts.append(text[j])
                    j += 1
            directives.append((start_line, "".join(parts).strip()))
            i = j
        else:
            line_start = False
            m = ident.match(text, i)
            if m:
                word, j = m.group(0), m.end()
                if word in STRING_PREFIXES and j < n and text[j] in "\"'":
                    if word.endswith("R") and text[j] == '"':  # raw string R"delim( ... )delim"
                        open_paren = text.find("(", j)
                        delim = text[j + 1:open_paren]
                        end = text.find(")" + delim + '"', open_paren)
                        end = n if end < 0 else end + len(delim) + 2
                        line += text.count("\n", j, end)
                        i = end
                    else:
                        i = skip_quoted(j, text[j])
                    tokens.append(Token("LIT", line))
                else:
                    tokens.append(Token(word, line))
                    i = j
            elif c.isdigit() or (c == "." and i + 1 < n and text[i + 1].isdigit()):
                tokens.append(Token("LIT", line))  # numbers, digit separators included
                i = number.match(text, i).end()
            elif c in "\"'":
                i = skip_quoted(i, c)
                tokens.append(Token("LIT", line))
            elif text[i:i + 2] in PUNCT2:
                tokens.append(Token(text[i:i + 2], line))
                i += 2
            else:
                tokens.append(Token(c, line))
                i += 1
    return tokens, directives


# ------------------------------------------------------------------------- declaration reading

def top_level(decl, stop):
    """Index of the first token in `stop` outside (), [] and {}, or -1."""
    depth = 0
    for k, tok in enumerate(decl):
        t = tok.text
        if depth == 0 and t in stop:
            return k
        if t in "([{":
            depth += 1
        elif t in ")]}":
            depth -= 1
    return -1


def open_parens(decl):
    depth = 0
    for x in decl:
        if x.text in "([":
            depth += 1
        elif x.text in ")]":
            depth -= 1
    return depth > 0


def skip_group(decl, i, opening, closing):
    """decl[i] opens a group: the index after its end."""
    depth = 0
    while i < len(decl):
        t = decl[i].text
        if t == opening:
            depth += 1
        elif t == closing:
            depth -= 1
            if depth == 0:
                return i + 1
        elif opening == "<" and t in ("(", ")"):  # parentheses inside template arguments
            depth += 100 if t == "(" else -100
        i += 1
    return i


def strip_noise(decl):
    """The declaration without attributes ([[...]], __attribute__((...)), alignas(...)) and template
    headers (template <...>); and whether it was a template."""
    out, i, templated = [], 0, False
    while i < len(decl):
        t = decl[i].text
        nxt = decl[i + 1].text if i + 1 < len(decl) else ""
        if t == "[" and nxt == "[":
            i = skip_group(decl, i, "[", "]")
        elif t in ("__attribute__", "alignas", "__declspec") and nxt == "(":
            i = skip_group(decl, i + 1, "(", ")")
        elif t == "template" and nxt == "<":
            templated = True
            i = skip_group(decl, i + 1, "<", ">")
        else:
            out.append(decl[i])
            i += 1
    return out, templated


def is_function_declarator(clean):
    """`T name(params) ...` (a function) rather than `T name(args)` (a variable initialized by a
    constructor): a name or operator before the first parenthesis, and no literal or expression
    opening the parameters."""
    k = top_level(clean, {"("})
    if k <= 0:
        return False
    words = [x.text for x in clean[:k]]
    if "operator" in words:
        return True
    first = clean[k + 1].text if k + 1 < len(clean) else ")"
    return IDENT.match(clean[k - 1].text) is not None and first not in ("LIT", "{}", "{", "-", "!")


def function_name(clean):
    """The unqualified name a function declaration declares, or None for a qualified one (a member
    or a function declared elsewhere)."""
    k = top_level(clean, {"("})
    words = [x.text for x in clean[:k]]
    if "operator" in words:
        o = words.index("operator")
        if o > 0 and words[o - 1] == "::":
            return None
        return Token("operator" + ("".join(words[o + 1:]) or "()"), clean[o].line)
    if k >= 2 and clean[k - 2].text == "::":
        return None
    name = clean[k - 1]
    return name if is_ident(name.text) and name.text not in TEST_MACROS else None


def declarator_names(decl):
    """The names a variable declaration (specifiers, then declarators) declares."""
    names = []
    parts, cur, depth, angle, in_init = [], [], 0, 0, False
    for tok in decl:  # split at top-level commas (not those of template arguments or initializers)
        t = tok.text
        if t in "([{":
            depth += 1
        elif t in ")]}":
            depth -= 1
        elif depth == 0 and not in_init and t in "<>":
            angle += 1 if t == "<" else -1
        elif depth == 0 and angle <= 0 and t == "=":
            in_init = True
        if depth == 0 and angle <= 0 and t == ",":
            parts.append(cur)
            cur, in_init, angle = [], False, 0
        else:
            cur.append(tok)
    parts.append(cur)
    for p, part in enumerate(parts):
        end = top_level(part, {"=", "[", "{", "{}", "("})
        head = part if end < 0 else part[:end]
        if end >= 0 and part[end].text == "(" and not head:
            continue
        if end >= 0 and part[end].text == "(" and end + 2 < len(part) and part[end + 1].text == "*":
            names.append(part[end + 2])  # T (*name)(...)
            continue
        idents = [t for t in head if is_ident(t.text)]
        if not idents:
            continue
        if p > 0:
            names.append(idents[0])
            continue
        last = head[-1]
        if is_ident(last.text) and not (len(head) > 1 and head[-2].text == "::"):
            names.append(last)
    return names


def enumerators(body):
    out, depth, expect = [], 0, True
    for x in body:
        if x.text in "([{":
            depth += 1
        elif x.text in ")]}":
            depth -= 1
        elif depth == 0 and x.text == ",":
            expect = True
            continue
        if depth == 0 and expect:
            if is_ident(x.text):
                out.append(x)
            expect = False
    return out


class Decl:
    __slots__ = ("name", "kind", "line", "ns", "local", "value")

    def __init__(self, name, kind, line, ns, local, value=""):
        self.name, self.kind, self.line, self.ns, self.local, self.value = name, kind, line, ns, local, value


class FileInfo:
    def __init__(self, path):
        self.path = path
        self.decls = []        # namespace-scope names (Decl); .local: defined for this file alone
        self.directives = []   # (line, namespace, where): using-directives at namespace scope
        self.tests = []        # (macro, suite, name, line)
        self.macros = []       # (name, line): defined and not #undef'd by the end
        self.namespaces = set()
        self.identifiers = set()

    def local(self):
        return [d for d in self.decls if d.local]


def read_macros(info, directives):
    """Macros defined and not #undef'd by the end of the file. `#ifndef X` / `#define X` (a default
    for a name the build may define) does not count: X is defined either way."""
    defined, cond = {}, []
    for line, d in directives:
        m = re.match(r"(\w+)\s*(.*)", d)
        if not m:
            continue
        kw, rest = m.group(1), m.group(2)
        word = re.match(r"\w+", rest)
        name = word.group(0) if word else ""
        if kw in ("if", "ifdef", "ifndef"):
            g = re.match(r"!\s*defined\s*\(?\s*(\w+)\s*\)?\s*$", rest)
            cond.append(name if kw == "ifndef" else g.group(1) if (kw == "if" and g) else "")
            info.identifiers.update(re.findall(r"[A-Za-z_]\w*", rest))
        elif kw == "endif" and cond:
            cond.pop()
        elif kw == "define" and name:
            if not (cond and cond[-1] == name):
                defined[name] = line
        elif kw == "undef" and name:
            defined.pop(name, None)
    info.macros = sorted(defined.items(), key=lambda x: x[1])


def parse_file(path, rel, is_source=True):
    """Reads a source (is_source: aliases, using-declarations and types at namespace scope count as
    the file's own) or a header (every namespace-scope name is recorded, for rule 2)."""
    with open(path, encoding="utf-8", errors="replace") as f:
        tokens, directives = lex(f.read())
    info = FileInfo(rel)
    info.identifiers = {t.text for t in tokens if IDENT.match(t.text)}
    read_macros(info, directives)

    scopes = [("", False)]  # namespaces: (qualified name, inside an anonymous namespace)
    n = len(tokens)

    def ns_name():
        return scopes[-1][0] or "(global)"

    def anon():
        return scopes[-1][1]

    def add(tok, kind, local, value=""):
        info.decls.append(Decl(tok.text, kind, tok.line, ns_name(), local, value))

    def skip_braces(k):
        depth = 0
        while k < n:
            t = tokens[k].text
            if t == "{":
                depth += 1
            elif t == "}":
                depth -= 1
                if depth == 0:
                    return k + 1
            k += 1
        return n

    def finish(decl, has_body=False):
        """Records what a complete namespace-scope declaration declares."""
        if not decl:
            return
        clean, templated = strip_noise(decl)
        if not clean:
            return
        words = [t.text for t in clean]
        if words[0] == "using":  # (an alias template is an alias)
            decl = clean
            if words[1:2] == ["namespace"]:
                info.directives.append((decl[0].line, "".join(words[2:]), ns_name()))
            elif len(words) > 2 and words[2] == "=":
                add(decl[1], "alias", anon() or is_source, " ".join(words[3:]))
            else:
                idents = [t for t in decl if IDENT.match(t.text)]
                if idents:
                    add(idents[-1], "using-declaration", anon() or is_source, "".join(words[1:]))
            return
        if words[0] == "namespace":  # namespace alias
            if len(words) > 2 and words[2] == "=":
                add(decl[1], "namespace alias", anon() or is_source, "".join(words[3:]))
            return
        if words[0] in ("static_assert", "friend") or words[0] in TEST_MACROS or words[0].startswith(
                ("INSTANTIATE_", "GTEST_", "REGISTER_TYPED_TEST")):
            return
        if words[0] == "extern" and words[1:2] != ["LIT"]:
            return  # a declaration of something defined elsewhere
        if words and words[0] == "__TYPE__":  # the declarators after a class body: struct {...} x;
            clean, words = clean[1:], words[1:]
        if not clean or words[0] == "template":  # explicit instantiation
            return
        t_suffix = " template" if templated else ""
        if words[0] == "typedef":
            k = top_level(clean, {"("})
            if k >= 0 and k + 2 < len(clean) and clean[k + 1].text == "*":
                add(clean[k + 2], "typedef", anon() or is_source, " ".join(words))
            else:
                idents = [t for t in clean if is_ident(t.text)]
                if idents:
                    add(idents[-1], "typedef", anon() or is_source, " ".join(words[1:-1]))
            return
        specifiers = words[: max(1, top_level(clean, {"(", "=", "{}"}))]
        static = "static" in specifiers
        if has_body or (top_level(clean, {"("}) >= 0 and top_level(clean, {"="}) < 0 and is_function_declarator(clean)):
            name = function_name(clean)
            if name is not None:  # a function of external linkage outside anonymous namespaces
                add(name, "function" + t_suffix, anon() or static)
            return
        # Namespace-scope constants have internal linkage (unless inline or extern).
        const = "constexpr" in specifiers or ("const" in specifiers and "inline" not in specifiers)
        for tok in declarator_names(clean):
            add(tok, "variable" + t_suffix, anon() or static or const)

    decl = []
    i = 0
    while i < n:
        tok = tokens[i]
        t = tok.text
        if t == ";" and not open_parens(decl):
            finish(decl)
            decl = []
            i += 1
        elif t == "}" and not open_parens(decl):
            finish(decl)
            decl = []
            if len(scopes) > 1:
                scopes.pop()
            i += 1
        elif t == "{":
            if open_parens(decl):  # a lambda or a braced argument inside parentheses
                decl.append(Token("{}", tok.line))
                i = skip_braces(i)
                continue
            words = [x.text for x in decl]
            if words[:1] == ["namespace"] or words[:2] == ["inline", "namespace"]:
                name = "".join(w for w in words if w not in ("namespace", "inline"))
                full = "::".join(x for x in (scopes[-1][0], name or "(anonymous)") if x)
                info.namespaces.add(full)
                scopes.append((full, anon() or not name))
                decl = []
                i += 1
                continue
            if words == ["extern", "LIT"]:  # extern "C" { ... }: the same scope
                scopes.append(scopes[-1])
                decl = []
                i += 1
                continue
            clean, templated = strip_noise(decl)
            cwords = [x.text for x in clean]
            end = skip_braces(i)
            if cwords[:1] and cwords[0] in ("class", "struct", "union", "enum") and top_level(clean, {"(", "="}) < 0:
                kind, rest = cwords[0], clean[1:]
                scoped = kind == "enum" and rest[:1] and rest[0].text in ("class", "struct")
                if scoped:
                    rest = rest[1:]
                colon = top_level(rest, {":"})
                head = rest if colon < 0 else rest[:colon]
                head = head[: top_level(head, {"<"})] if top_level(head, {"<"}) >= 0 else head
                names = [x for x in head if is_ident(x.text) and x.text != "final"]
                if names and not any(x.text == "::" for x in head):
                    add(names[-1], kind + (" template" if templated else ""), anon() or is_source)
                if kind == "enum" and not scoped:
                    for e in enumerators(tokens[i + 1:end - 1]):
                        add(e, "enumerator", anon() or is_source)
                decl = [Token("__TYPE__", tok.line)]
                i = end
                continue
            if cwords[:1] and cwords[0] in TEST_MACROS and len(clean) >= 5 and clean[1].text == "(":
                info.tests.append((cwords[0], clean[2].text, clean[4].text, clean[0].line))
                decl = []
                i = end
                continue
            if top_level(clean, {"="}) >= 0 or not is_function_declarator(clean):
                decl.append(Token("{}", tok.line))  # an initializer: `T x = {...}`, `T x{...}`
                i = end
                continue
            finish(decl, has_body=True)  # a function definition
            decl = []
            i = end
        else:
            decl.append(tok)
            i += 1
    return info


# ------------------------------------------------------------------------------------- checks

def skip_list(source_dir, cmakelists):
    """Sources a CMakeLists.txt marks SKIP_UNITY_BUILD_INCLUSION (paths relative to source_dir)."""
    path = os.path.join(source_dir, cmakelists)
    if not os.path.exists(path):
        return set()
    with open(path, encoding="utf-8") as f:
        text = re.sub(r"#[^\n]*", "", f.read())
    base = os.path.dirname(cmakelists)
    skipped = set()
    for m in re.finditer(r"set_source_files_properties\s*\((.*?)\)", text, re.S):
        if "SKIP_UNITY_BUILD_INCLUSION" in m.group(1):
            for word in m.group(1).split():
                if word.endswith((".cpp", ".cc", ".cxx")):
                    skipped.add(os.path.normpath(os.path.join(base, word)))
    return skipped


def canonical(target, ns, namespaces):
    """A using-declaration's target, qualified from the global namespace (as far as the project's
    own namespaces go), so that `testing::X` in alphaflex and `alphaflex::testing::X` compare equal."""
    target = target.lstrip(":")
    head = target.split("::")[0]
    parts = [p for p in ns.split("::") if p and p != "(anonymous)" and p != "(global)"]
    for k in range(len(parts), 0, -1):
        if "::".join(parts[:k] + [head]) in namespaces:
            return "::".join(parts[:k] + [target])
    return target


def check_target(target, source_dir, list_names):
    rels = set()
    for pattern in target["sources"]:
        rels.update(os.path.relpath(p, source_dir) for p in glob.glob(os.path.join(source_dir, pattern), recursive=True))
    rels = sorted(r for r in rels if r not in target["excluded"])
    skipped = skip_list(source_dir, target["cmakelists"])
    infos = [parse_file(os.path.join(source_dir, r), r) for r in rels]
    headers = set()
    for pattern in target["headers"]:
        headers.update(os.path.relpath(p, source_dir) for p in glob.glob(os.path.join(source_dir, pattern), recursive=True))
    header_infos = [parse_file(os.path.join(source_dir, h), h, is_source=False) for h in sorted(headers)]
    namespaces = set().union(*(i.namespaces for i in infos + header_infos))
    name = target["name"]
    problems = []

    if list_names:
        for info in infos:
            print(f"{name}: {info.path}" + (" (compiled alone)" if info.path in skipped else ""))
            for d in sorted(info.local(), key=lambda d: d.line):
                print(f"  {d.line:6d}  {d.kind:20s} {d.name}  [{d.ns}]")
            for line, ns, where in info.directives:
                print(f"  {line:6d}  using namespace {ns}  [{where}]")
            for macro, line in info.macros:
                print(f"  {line:6d}  macro {macro} (not #undef'd)")
    batched = [info for info in infos if info.path not in skipped]

    # 1. A name two sources define for themselves.
    owners = defaultdict(list)
    for info in batched:
        for d in info.local():
            value = canonical(d.value, d.ns, namespaces) if d.kind == "using-declaration" else d.value
            owners[d.name].append((info.path, d.line, d.kind, value))
    for nm in sorted(owners):
        defs = owners[nm]
        if len({p for p, _, _, _ in defs}) < 2:
            continue
        if all(k in REDECLARABLE for _, _, k, _ in defs) and len({(k, v) for _, _, k, v in defs}) == 1:
            continue
        first = {}
        for p, line, k, _ in defs:
            first.setdefault(p, (line, k))
        where = ", ".join(f"{p}:{line} ({k})" for p, (line, k) in first.items())
        problems.append(f"{name}: '{nm}' is defined for itself by {len(first)} sources: {where}")

    # 2. A name a source defines for itself that a shared header declares.
    declared = defaultdict(list)
    for h in header_infos:
        for d in h.decls:
            if "(anonymous)" not in d.ns:
                declared[d.name].append(f"{h.path}:{d.line}")
    for info in batched:
        for d in info.local():
            if d.name in declared and d.kind not in ("using-declaration", "namespace alias") and not d.name.startswith(
                    "operator"):  # operators overload on the file's own types
                problems.append(f"{name}: {info.path}:{d.line}: '{d.name}' ({d.kind}) is also a name of the shared "
                                f"header {declared[d.name][0]}: in a batch it would join or hide it for the next sources")

    # 3. Using-directives at namespace scope.
    for info in batched:
        for line, ns, where in info.directives:
            problems.append(f"{name}: {info.path}:{line}: 'using namespace {ns};' at namespace scope ({where}) stays "
                            f"in force for the next sources of a batch: open the code inside the namespace instead")

    # 4. Macros left defined that another source uses.
    for info in batched:
        for macro, line in info.macros:
            users = [o.path for o in batched if o is not info and macro in o.identifiers]
            if users:
                problems.append(f"{name}: {info.path}:{line}: macro {macro} is left defined (no #undef) and "
                                f"{', '.join(users)} use the name")

    # 5. GoogleTest names.
    tests, suites = defaultdict(list), defaultdict(set)
    for info in infos:
        for macro, suite, test, line in info.tests:
            tests[(suite, test)].append(f"{info.path}:{line}")
            suites[suite].add((macro, info.path))
    for (suite, test), where in sorted(tests.items()):
        if len(where) > 1:
            problems.append(f"{name}: test {suite}.{test} is defined {len(where)} times: {', '.join(where)}")
    for suite, uses in sorted(suites.items()):
        macros = {m for m, _ in uses}
        if "TEST" in macros and len(macros) > 1:
            problems.append(f"{name}: suite {suite} is used with {' and '.join(sorted(macros))} "
                            f"({', '.join(sorted({p for _, p in uses}))})")

    summary = (f"{name}: {len(rels)} sources ({len(rels) - len(batched)} compiled alone), "
               f"{sum(len(i.local()) for i in infos)} file-local names, {sum(len(i.tests) for i in infos)} tests")
    return problems, summary


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--source-dir", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    ap.add_argument("--list", action="store_true", help="print every file-local name read, per source")
    args = ap.parse_args()
    source_dir = os.path.normpath(args.source_dir)
    problems, summaries = [], []
    for target in TARGETS:
        p, s = check_target(target, source_dir, args.list)
        problems += p
        summaries.append(s)
    for p in problems:
        print(p)
    for s in summaries:
        print(s)
    if problems:
        print(f"check_unity_names: {len(problems)} problem(s): these sources cannot share a unity batch")
        return 1
    print("check_unity_names: no clashes")
    return 0


if __name__ == "__main__":
    sys.exit(main())
