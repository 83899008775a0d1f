#!/usr/bin/python3
"""generate_ros_api: docs/ros_api.md from the code of the ROS layer.

    scripts/generate_ros_api.py            print the page
    scripts/generate_ros_api.py --check    exit 1 when docs/ros_api.md differs from it
    scripts/generate_ros_api.py --write    rewrite docs/ros_api.md

Parses (no build, no ROS): nodes/*.cpp (one node per file), the functions and classes of
src/ros/*.cpp and include/reach_trajopt/ros/*.h that a node uses (by name, transitively), and
msg/, srv/, action/. It finds
  publishers      <handle>.advertise<Type>("name", queue[, latch]), tf2_ros::TransformBroadcaster
  subscribers     <handle>.subscribe("name", queue, &Class::callback, ...) (type: the callback's)
  services        <handle>.advertiseService("name", &Class::method, ...) (type: the method's)
  actions         SimpleActionServer<pkg::XAction> aliases constructed with (nh, "name", ...)
  service clients ServiceCall / ServiceConnection / serviceClient <pkg::X>, the name through the
                  variable handed to it, back to the parameter that sets it
  parameters      param(pnh, "name", default), pnh.getParam("name", var) (default: the
                  variable's initializer or what the code assigns when the parameter is unset)
Descriptions come from the node's header comment (the text after `~name`). A private handle is
one constructed with "~"; names on it are written ~name.
"""
import os
import re
import sys

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
OUT = os.path.join(REPO, "docs", "ros_api.md")


def read(path):
    with open(path) as f:
        return f.read()


def string_end(code, i):
    """The index after the string literal that starts at code[i] (a '"')."""
    j, n = i + 1, len(code)
    while j < n and code[j] != '"':
        j += 2 if code[j] == "\\" else 1
    return j + 1


def strip_comments(code):
    """Code without // and /* */ comments (string literals kept)."""
    out, i, n = [], 0, len(code)
    while i < n:
        c = code[i]
        if c == '"':
            j = string_end(code, i)
            out.append(code[i:j])
            i = j
        elif code.startswith("//", i):
            j = code.find("\n", i)
            i = n if j < 0 else j
        elif code.startswith("/*", i):
            j = code.find("*/", i + 2)
            i = n if j < 0 else j + 2
        else:
            out.append(c)
            i += 1
    return "".join(out)


def header_comment(code):
    """The leading /// block of a file, joined into one line."""
    lines = []
    for line in code.splitlines():
        if line.startswith("///"):
            lines.append(line[3:].strip())
        elif lines:
            break
    return " ".join(lines)


def units(code):
    """{name: body text} of the top-level functions and classes of a C++ file.

    A function `A::b(...) {` is keyed "A" (its class) and "A::b", a free function by its name,
    a class or struct by its name; namespaces are transparent."""
    code = strip_comments(code)
    out = {}
    i, n, start = 0, len(code), 0
    depth_ns = 0
    while i < n:
        c = code[i]
        if c == '"':
            i = string_end(code, i)
            continue
        if c in ";}":
            start = i + 1
        if c == "{":
            head = code[start:i]
            if re.search(r"\bnamespace\b[\w\s:]*$", head) or re.search(r'extern\s+"C"\s*$', head):
                depth_ns += 1
                start = i + 1
                i += 1
                continue
            # find the matching brace
            depth, j = 0, i
            while j < n:
                if code[j] == '"':
                    j = string_end(code, j)
                    continue
                if code[j] == "{":
                    depth += 1
                elif code[j] == "}":
                    depth -= 1
                    if depth == 0:
                        break
                j += 1
            body = head + code[i:j + 1]
            m = re.search(r"\b(class|struct)\s+(\w+)[^(]*$", head)
            if m:
                out.setdefault(m.group(2), "")
                out[m.group(2)] += body
            else:
                m = re.search(r"((?:\w+::)*~?\w+)\s*\(", head)
                if m:
                    name = m.group(1)
                    parts = name.split("::")
                    keys = [name, parts[-1]] if len(parts) == 1 else [name, parts[-2]]
                    for k in keys:
                        out.setdefault(k, "")
                        out[k] += body
            i = j + 1
            start = i
            continue
        i += 1
    return out


LIB_DOCS = {}  # unit name -> the /// comments of the files that define it


def doc_comments(code):
    """Every /// comment of a file, joined into one line."""
    return " ".join(l.strip()[3:].strip() for l in code.splitlines() if l.strip().startswith("///"))


def library_units():
    lib = {}
    for d, ext in (("src/ros", ".cpp"), ("include/reach_trajopt/ros", ".h")):
        folder = os.path.join(REPO, d)
        if not os.path.isdir(folder):
            continue
        for f in sorted(os.listdir(folder)):
            if f.endswith(ext):
                code = read(os.path.join(folder, f))
                for k, body in units(code).items():
                    lib[k] = lib.get(k, "") + body
                    LIB_DOCS[k] = LIB_DOCS.get(k, "") + " " + doc_comments(code)
    return lib


def used_code(node_code, lib):
    """The node's code and every library unit it uses, transitively (by word match)."""
    seen, todo, texts = set(), [node_code], [node_code]
    while todo:
        text = todo.pop()
        words = set(re.findall(r"\b\w+(?:::\w+)*\b", text))
        flat = set()
        for w in words:
            parts = w.split("::")
            flat.update(parts)
            for k in range(len(parts) - 1):
                flat.add("::".join(parts[k:]))
        for name in sorted(flat & set(lib)):
            if name not in seen and "::" not in name:
                seen.add(name)
                todo.append(lib[name])
                texts.append(lib[name])
    return texts


def short_type(t):
    t = t.strip().replace(" ", "")
    t = re.sub(r"(ConstPtr|::ConstPtr|Ptr)$", "", t)
    return t.split("::")[-1] if t.startswith("reach_trajopt::") else t.replace("::", "/")


def literal(expr):
    expr = " ".join(expr.split())
    m = re.fullmatch(r'"(.*)"', expr)
    if m:
        return m.group(1) if m.group(1) else '""'
    return expr


def handles(code):
    """{handle variable: '~' or ''}: ros::NodeHandle nh, pnh("~")."""
    out = {}
    for m in re.finditer(r"ros::NodeHandle\s+([^;]*);", code):
        for part in m.group(1).split(","):
            pm = re.match(r"\s*&?\s*(\w+)\s*(\(\s*\"~\"\s*\))?", part)
            if pm:
                out[pm.group(1)] = "~" if pm.group(2) else ""
    for m in re.finditer(r"(?:const\s+)?ros::NodeHandle\s*&\s*(\w+)", code):
        out.setdefault(m.group(1), "~" if m.group(1).startswith("p") else "")
    return out


def resolve_name(h, name, hmap):
    if name.startswith("/") or name.startswith("~"):
        return name
    return ("~" if hmap.get(h) == "~" else "") + name


def describe(doc, pname):
    """The header comment's words on `~pname`: the bracket groups after it ([unit, default]
    (meaning)), else the text to the next parameter or sentence."""
    hits = list(re.finditer(r"~" + re.escape(pname) + r"\b(?![>'])", doc))
    if not hits:
        return ""
    best = next((h for h in hits if re.match(r"\s*[\[(]", doc[h.end():])), hits[0])
    text = doc[best.end():]
    groups, i = [], 0
    while True:
        mm = re.match(r"\s*([\[(])", text[i:])
        if not mm:
            break
        open_c = mm.group(1)
        close_c = "]" if open_c == "[" else ")"
        j, depth = i + mm.end() - 1, 0
        while j < len(text):
            if text[j] == open_c:
                depth += 1
            elif text[j] == close_c:
                depth -= 1
                if depth == 0:
                    break
            j += 1
        groups.append(text[i + mm.end() - 1:j + 1].strip())
        i = j + 1
    if groups:
        out = " ".join(g[1:-1] if g.startswith("(") else g for g in groups)
    else:
        cut = len(text)
        for pat in (r",\s*~\w", r"\.\s+[A-Z~(]", r";\s*~\w", r"\)"):
            mm = re.search(pat, text)
            if mm:
                cut = min(cut, mm.start())
        out = text[:cut]
    out = out.strip(" ,.:;")
    if len(out) > 220:
        out = out[:217].rsplit(" ", 1)[0] + " ..."
    return out.replace("|", "\\|")


def var_default(code, var, before):
    """What `var` holds when its parameter is unset: its initializer before `before`."""
    head = code[:before]
    pat = (r"(?:\b[\w:<>]+\s+|,\s*)" + re.escape(var) +
           r"\s*(?:=\s*([^,;{}]+?)\s*[,;]|\{([^{}]*)\}|\(([^()]*)\)\s*[,;])")
    found = None
    for m in re.finditer(pat, head):
        found = m
    if found:
        val = next(g for g in found.groups() if g is not None).strip()
        return literal(val) if val else "(empty)"
    m = None
    for m in re.finditer(r"[:,]\s*" + re.escape(var) + r"\(([^()]*(?:\([^()]*\))?[^()]*)\)", head):
        pass
    if m and var.endswith("_"):
        return literal(m.group(1))
    return None


def member_default(var, text):
    """`root.member` where root is declared `Type root;`: Type's default of member, from the
    headers of include/."""
    parts = var.split(".")
    if len(parts) != 2:
        return None
    m = re.search(r"\b(\w+)\s+" + re.escape(parts[0]) + r"\s*;", text)
    if not m:
        return None
    for root, _, files in os.walk(os.path.join(REPO, "include")):
        for f in files:
            code = strip_comments(read(os.path.join(root, f)))
            sm = re.search(r"\b(?:struct|class)\s+" + m.group(1) + r"\b[^{;]*\{", code)
            if sm:
                dm = re.search(r"\b" + re.escape(parts[1]) + r"\s*=\s*([^;]+);", code[sm.end():])
                if dm:
                    return literal(dm.group(1))
                if re.search(r"\bstd::string\s+" + re.escape(parts[1]) + r"\s*;", code[sm.end():]):
                    return '""'
    return None


def get_param_default(text, m):
    """The value a getParam call's variable keeps when the parameter is unset."""
    var = m.group(3)
    before = text[:m.start()]
    tail = text[m.end():m.end() + 300]
    negated = re.search(r"if\s*\(\s*!\s*$", before)
    positive = re.search(r"if\s*\(\s*$", before)
    if negated:
        if re.match(r"\s*\|\|[^;{]*\)\s*throw", tail):
            return "(required)"
        um = re.match(r"\s*\)\s*(\w+)\s*=\s*([^;]+);", tail)
        if um:
            return literal(um.group(2))
    if positive:
        am = re.match(r"\s*\)\s*\{?\s*(?:if[^;]*;\s*)?([\w.]+)\s*=", tail)
        if am:
            return "`%s`" % am.group(1)
    if "." in var:
        # `root.member = expr;` before the call (a default computed at run time)
        assigned = None
        for am in re.finditer(r"\b" + re.escape(var) + r"\s*=\s*([^;=]+?)\s*;", before):
            assigned = am
        if assigned:
            return "`%s`" % " ".join(assigned.group(1).split())
        d = member_default(var, text)
        return d if d is not None else "`%s`" % var
    d = var_default(text, var, len(text) if var.endswith("_") else m.start())
    if d == "(empty)":
        return '""'
    return d if d is not None else "`%s`" % var


def scan_node(name, node_code, lib):
    texts = used_code(strip_comments(node_code), lib)
    code = "\n".join(texts)
    hmap = handles(code)
    doc = header_comment(node_code)
    # a parameter the node's own header does not describe: the comments of the library files
    # whose code the node uses (a thin node keeps its interface there)
    lib_doc = " ".join(sorted({LIB_DOCS[k] for k in lib if lib[k] in texts[1:] and k in LIB_DOCS}))
    pubs, subs, srvs, acts, clients, params = [], [], [], [], [], {}

    for m in re.finditer(r"(\w+)\s*(?:\.|->)\s*advertise\s*<\s*([\w:]+)\s*>\s*\(\s*([^,]+?)\s*,"
                         r"\s*(\w+)\s*(,\s*(true|false))?", code):
        h, typ, topic, latch = m.group(1), m.group(2), m.group(3), m.group(6) == "true"
        topic = literal(topic)
        if not re.fullmatch(r"[\w/~]+", topic):
            topic = re.sub(r'"\s*\+\s*.*', "<…>", topic.strip('"')) if topic.startswith('"') \
                else "(computed: %s)" % topic
        pubs.append((resolve_name(h, topic, hmap), short_type(typ), "latched" if latch else ""))
    if re.search(r"tf2_ros::TransformBroadcaster", code):
        pubs.append(("/tf", "tf2_msgs/TFMessage", ""))

    def callback_type(method):
        m = re.search(r"\b" + re.escape(method) +
                      r"\s*\(\s*const\s+([\w:]+?)(?:::ConstPtr|ConstPtr)?\s*&", code)
        return short_type(m.group(1)) if m else "?"

    for m in re.finditer(r"(\w+)\s*(?:\.|->)\s*subscribe\s*(?:<\s*([\w:]+)\s*>)?\s*\(\s*\"([^\"]+)\""
                         r"\s*,\s*\w+\s*,\s*&\s*(?:\w+::)*(\w+)", code):
        typ = short_type(m.group(2)) if m.group(2) else callback_type(m.group(4))
        subs.append((resolve_name(m.group(1), m.group(3), hmap), typ))

    for m in re.finditer(r"(\w+)\s*(?:\.|->)\s*advertiseService\s*\(\s*\"([^\"]+)\"\s*,\s*&\s*"
                         r"(?:\w+::)*(\w+)", code):
        mm = re.search(r"\b" + re.escape(m.group(3)) + r"\s*\(\s*([\w:]+)::Request\s*&", code)
        typ = short_type(mm.group(1)) if mm else "?"
        srvs.append((resolve_name(m.group(1), m.group(2), hmap), typ))

    aliases = {a.group(1): a.group(2) for a in re.finditer(
        r"using\s+(\w+)\s*=\s*actionlib::SimpleActionServer\s*<\s*([\w:]+?)Action\s*>", code)}
    for alias, typ in aliases.items():
        for m in re.finditer(r"\b" + alias + r"\s*>?\s*\(\s*(\w+)\s*,\s*\"([^\"]+)\"", code):
            acts.append((resolve_name(m.group(1), m.group(2), hmap), short_type(typ)))

    def param_of(var, at):
        """The parameter that sets variable `var` (name, default) or None."""
        head = code[:at] if at is not None else code
        for m in re.finditer(r"\b" + re.escape(var) + r"\s*=\s*param\s*(?:<[^>]*>)?\s*\(\s*\w+\s*,"
                             r"\s*\"(\w+)\"\s*,\s*([^;]+?)\)\s*;", code):
            return m.group(1), literal(m.group(2))
        for m in re.finditer(r"getParam\s*\(\s*\"(\w+)\"\s*,\s*" + re.escape(var) + r"\s*\)", code):
            return m.group(1), None
        for m in re.finditer(re.escape(var) + r"\s*\.\s*push_back\s*\(\s*(\w+)", head):
            return param_of(m.group(1), m.start())
        # `var = params_.member;`: the parameter read into some struct's `member`
        for m in re.finditer(r"\b" + re.escape(var) + r"\s*=\s*\w+\s*\.\s*(\w+)\s*;", head):
            for g in re.finditer(r"getParam\s*\(\s*\"(\w+)\"\s*,\s*\w+\s*\.\s*" +
                                 re.escape(m.group(1)) + r"\s*\)", code):
                return g.group(1), None
        return None

    # service clients: a client template with a service type, the name from a variable
    client_types = {}
    for text in texts:
        for m in re.finditer(r"(?:ServiceCall|ServiceConnection|serviceClient)\s*<\s*"
                             r"(reach_trajopt::\w+)\s*>", text):
            owner = None
            for k, body in lib.items():
                if body == text and "::" not in k:
                    owner = k
            client_types.setdefault(short_type(m.group(1)), owner)
    for typ, owner in sorted(client_types.items()):
        via = ""
        # the construction in the node: `<...Type> var(nh, NAME` or `Owner>(nh, NAME`
        pats = [r"<\s*reach_trajopt::" + typ + r"\s*>\s*\w+\s*\(\s*\w+\s*,\s*(\w+)"]
        if owner:
            pats.append(r"\b" + owner + r"\s*>?\s*\(\s*\w+\s*,\s*(\w+)")
        for p in pats:
            m = re.search(p, code)
            if m:
                hit = param_of(m.group(1), m.start())
                if hit:
                    via = "~" + hit[0]
                break
        clients.append((typ, via))

    # parameters, unit by unit (a variable's initializer is looked up in its own unit)
    for text in texts:
        for m in re.finditer(r"\bparam\s*(?:<[^>]*>)?\s*\(\s*(\w+)\s*,\s*\"(\w+)\"\s*,\s*"
                             r"([^;]+?)\)\s*;", text):
            params.setdefault(resolve_name(m.group(1), m.group(2), hmap), literal(m.group(3)))
        for m in re.finditer(r"(\w+)\s*\.\s*getParam\s*\(\s*\"([\w/]+)\"\s*,\s*"
                             r"([\w.]+(?:\(\))?)\s*\)", text):
            key = resolve_name(m.group(1), m.group(2), hmap)
            params.setdefault(key, get_param_default(text, m))
    rows = []
    for key in sorted(params, key=lambda k: (not k.startswith("~"), k)):
        d = params[key]
        d = d if d.startswith("`") or d in ("(required)", '""') else "`%s`" % d
        d = d.replace('ros::package::getPath("reach_trajopt") + "/', "$(find reach_trajopt)/")
        d = re.sub(r'"`$', "`", d)
        if key.startswith("~"):
            desc = describe(doc, key[1:]) or describe(lib_doc, key[1:])
        else:  # a global parameter: "the `name` parameter (meaning)" in the header comment
            gm = re.search(r"`%s`\s+parameter\s+\(([^)]*)\)" % re.escape(key.lstrip("/")), doc)
            desc = gm.group(1) if gm else ""
        rows.append((key, d, desc))
    return {
        "name": name, "doc": doc, "pubs": sorted(set(pubs)), "subs": sorted(set(subs)),
        "srvs": sorted(set(srvs)), "acts": sorted(set(acts)), "clients": clients, "params": rows,
    }


def sentence(text, limit=220):
    """The first sentence of text (not cut at "Sec.", "eq.", "e.g.")."""
    m = re.search(r"(?<!Sec)(?<!eq)(?<!e\.g)(?<!i\.e)(?<!Fig)(?<!Prop)[.:](\s|$)", text)
    out = text[:m.start() + 1].rstrip(":") if m else text
    if len(out) > limit:
        out = out[:limit - 3].rsplit(" ", 1)[0] + " ..."
    return out.replace("|", "\\|")


def first_comment(path):
    lines = []
    for line in read(path).splitlines():
        line = line.strip()
        if line.startswith("#"):
            lines.append(line.lstrip("# "))
        elif line or lines:
            break
    return sentence(" ".join(lines))


def fields(path):
    """`type name` of every field, sections of a srv/action split by ---."""
    parts, cur = [], []
    for line in read(path).splitlines():
        s = line.split("#", 1)[0].strip()
        if s == "---":
            parts.append(cur)
            cur = []
        elif s:
            cur.append(" ".join(s.split()[:2]))
    parts.append(cur)
    return ["; ".join(p) if p else "(empty)" for p in parts]


def generate():
    lib = library_units()
    nodes_dir = os.path.join(REPO, "nodes")
    nodes = [scan_node(os.path.splitext(f)[0], read(os.path.join(nodes_dir, f)), lib)
             for f in sorted(os.listdir(nodes_dir)) if f.endswith(".cpp")]
    L = ["# ROS interface",
         "",
         "Generated by `scripts/generate_ros_api.py` from `nodes/*.cpp`, `src/ros/`,",
         "`include/reach_trajopt/ros/`, `msg/`, `srv/` and `action/`; `make test` fails when this",
         "file differs from what the script prints (regenerate: `scripts/generate_ros_api.py",
         "--write`). How the nodes work together: [ros_graph.md](ros_graph.md). Names without a",
         "leading `/` are relative (remappable); `~name` is a node's private parameter.",
         ""]
    L += ["## Nodes", "", "| node | what it is |", "|---|---|"]
    for n in nodes:
        first = sentence(n["doc"].split(": ", 1)[-1])
        L.append("| `%s` | %s |" % (n["name"], first.replace("|", "\\|")))
    L.append("")
    L += ["## Topics", "", "| topic | type | publishers | subscribers |", "|---|---|---|---|"]
    topics = {}
    for n in nodes:
        for t, typ, latch in n["pubs"]:
            e = topics.setdefault(t, [set(), set(), set()])
            e[0].add(typ + (" (latched)" if latch else ""))
            e[1].add(n["name"])
        for t, typ in n["subs"]:
            e = topics.setdefault(t, [set(), set(), set()])
            e[0].add(typ)
            e[2].add(n["name"])
    for t in sorted(topics, key=lambda s: s.lstrip("/")):
        typ, p, s = topics[t]
        L.append("| `%s` | %s | %s | %s |" % (t, ", ".join(sorted(typ)),
                                             ", ".join(sorted(p)) or "-", ", ".join(sorted(s)) or "-"))
    L.append("")
    L += ["## Services", "", "| service | type | served by | called by |", "|---|---|---|---|"]
    served = {}
    for n in nodes:
        for s, typ in n["srvs"]:
            served.setdefault(typ, []).append((s, n["name"]))
    callers = {}
    for n in nodes:
        for typ, via in n["clients"]:
            callers.setdefault(typ, []).append("%s%s" % (n["name"], " (name: `%s`)" % via if via
                                                         else ""))
    for typ in sorted(set(served) | set(callers)):
        for s, node in served.get(typ, [("?", "-")]):
            L.append("| `%s` | %s | %s | %s |" % (s, typ, node,
                                                 ", ".join(callers.get(typ, [])) or "-"))
    L.append("")
    L += ["## Actions", "", "| action | type | served by |", "|---|---|---|"]
    for n in nodes:
        for a, typ in n["acts"]:
            L.append("| `%s` | %s | %s |" % (a, typ, n["name"]))
    L.append("")
    L += ["## Parameters", "",
          "Defaults as the code sets them when the parameter is unset (`launch/walk.launch` sets",
          "some of them): a value, or in backticks the config key or code expression the node",
          "keeps (`walk.steps`: the key of `~config`); the meaning is the node's header comment.",
          "",
          "| node | parameter | default | meaning |", "|---|---|---|---|"]
    for n in nodes:
        for key, d, desc in n["params"]:
            L.append("| `%s` | `%s` | %s | %s |" % (n["name"], key, d, desc or "-"))
    L.append("")
    L += ["## Messages, services and actions of the package", "",
          "| file | fields (request --- response, goal --- result --- feedback) | comment |",
          "|---|---|---|"]
    for d in ("msg", "srv", "action"):
        folder = os.path.join(REPO, d)
        if not os.path.isdir(folder):
            continue
        for f in sorted(os.listdir(folder)):
            p = os.path.join(folder, f)
            flds = " --- ".join(fields(p))
            if len(flds) > 300:
                flds = flds[:297].rsplit(";", 1)[0] + "; ..."
            L.append("| `%s/%s` | %s | %s |" % (d, f, flds.replace("|", "\\|"), first_comment(p)))
    L.append("")
    return "\n".join(L)


def main(argv):
    text = generate()
    if "--write" in argv:
        with open(OUT, "w") as f:
            f.write(text)
        return 0
    if "--check" in argv:
        old = read(OUT) if os.path.isfile(OUT) else ""
        if old != text:
            print("docs/ros_api.md is out of date: regenerate it with\n"
                  "  scripts/generate_ros_api.py --write", file=sys.stderr)
            return 1
        return 0
    sys.stdout.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
