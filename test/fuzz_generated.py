#!/usr/bin/env python3
"""Generated fuzz family: malformed Gmsh files and expressions, drawn from a fixed seed.

Usage: fuzz_generated.py ANISODWR SOURCE_DIR [--seed S] [--cases N]

Each case mutates a valid input: a 3x2 quadrilateral mesh in Gmsh format 2.2 (nodes
dropped, duplicated or moved onto each other, coordinates that are not finite or out of
range, triangles, degenerate or reordered cells, wrong counts, truncation, garbage
lines, a header of another format, physical tags out of range) or an expression of the
custom scene (random token strings in scene.rhs, scene.initial_value, scene.dirichlet,
scene.convection and scene.reaction). Every case must end within 20 s with

  exit 0 and summary.json's status "ok" (the mutation left a valid input), or
  exit 2 with a message that names the mesh file (mesh cases) or the key (expressions),
or exit 3 naming the loop (finite data that overflow in the computation, e.g. 1e308);

never a signal, a timeout, exit 1, or exit 3 without the loop. A failed case prints its input, so that it can be added to the fixed corpus
(fuzz_inputs.sh) once fixed.
"""
import json
import os
import random
import subprocess
import sys
import tempfile

NODES = [(1, 0, 0), (2, 1, 0), (3, 2, 0), (4, 3, 0), (5, 0, 1), (6, 1, 1), (7, 2, 1),
         (8, 3, 1), (9, 0, 2), (10, 1, 2), (11, 2, 2), (12, 3, 2)]
# counter-clockwise quadrilaterals, physical tag 10
QUADS = [(1, 2, 6, 5), (2, 3, 7, 6), (3, 4, 8, 7), (5, 6, 10, 9), (6, 7, 11, 10),
         (7, 8, 12, 11)]
# boundary lines with physical tags 1 (left, x = 0) and 2 (the rest)
LINES = [(1, 1, 5), (1, 5, 9), (2, 1, 2), (2, 2, 3), (2, 3, 4), (2, 4, 8), (2, 8, 12),
         (2, 12, 11), (2, 11, 10), (2, 10, 9)]


def mesh_parts():
    nodes = [[str(i), repr(float(x)), repr(float(y)), "0"] for i, x, y in NODES]
    elements = [["1", str(tag), str(a), str(b)] for tag, a, b in LINES]
    elements += [["3", "10"] + [str(v) for v in q] for q in QUADS]
    return nodes, elements


def write_mesh(nodes, elements, header="2.2 0 8", node_count=None, elem_count=None,
               cut=None, extra=None):
    lines = ["$MeshFormat", header, "$EndMeshFormat", "$Nodes",
             str(len(nodes) if node_count is None else node_count)]
    lines += [" ".join(n) for n in nodes]
    lines += ["$EndNodes", "$Elements",
              str(len(elements) if elem_count is None else elem_count)]
    for k, e in enumerate(elements):
        # number type ntags physical elementary nodes...
        lines.append(" ".join([str(k + 1), e[0], "2", e[1], e[1]] + e[2:]))
    lines.append("$EndElements")
    if extra is not None:
        lines.insert(extra[0], extra[1])
    if cut is not None:
        lines = lines[:cut]
    return "\n".join(lines) + "\n"


def mutate_mesh(rng):
    """One malformed (or possibly still valid) mesh file and what was done to it."""
    nodes, elements = mesh_parts()
    quad_rows = [k for k, e in enumerate(elements) if e[0] == "3"]
    kind = rng.choice(["drop_node", "duplicate_tag", "bad_coordinate", "triangle",
                       "repeated_node", "swap_nodes", "reverse", "node_count",
                       "element_count", "truncate", "garbage", "header", "tag",
                       "short_element", "merge_nodes", "scale", "duplicate_cell",
                       "unknown_type"])
    kw = {}
    if kind == "drop_node":
        del nodes[rng.randrange(len(nodes))]
    elif kind == "duplicate_tag":
        src = rng.choice(nodes)
        nodes.append([src[0], repr(rng.uniform(-1, 4)), repr(rng.uniform(-1, 3)), "0"])
    elif kind == "bad_coordinate":
        n = rng.choice(nodes)
        n[rng.choice([1, 2])] = rng.choice(["nan", "inf", "-inf", "1e400", "abc", "",
                                            "1e300", "-1e-320"])
    elif kind == "triangle":
        e = elements[rng.choice(quad_rows)]
        del e[2 + rng.randrange(4)]
        e[0] = "2"
    elif kind == "repeated_node":
        e = elements[rng.choice(quad_rows)]
        i = 2 + rng.randrange(4)
        e[i] = e[2 + (i - 1) % 4]
    elif kind == "swap_nodes":
        e = elements[rng.choice(quad_rows)]
        i, j = rng.sample(range(2, 6), 2)
        e[i], e[j] = e[j], e[i]
    elif kind == "reverse":
        e = elements[rng.choice(quad_rows)]
        e[2:] = e[2:][::-1]
    elif kind == "node_count":
        kw["node_count"] = rng.choice([0, len(nodes) - 1, len(nodes) + 3, -1, 10**12])
    elif kind == "element_count":
        kw["elem_count"] = rng.choice([0, len(elements) - 1, len(elements) + 3, -5])
    elif kind == "truncate":
        kw["cut"] = rng.randrange(1, 8 + len(nodes) + len(elements))
    elif kind == "garbage":
        kw["extra"] = (rng.randrange(1, 8 + len(nodes) + len(elements)),
                       rng.choice(["xyz", "1 2", "$Nodes", "-", "3 10 1 2", "\x01\x02"]))
    elif kind == "header":
        kw["header"] = rng.choice(["4.1 0 8", "2.2 1 8", "1.0", "", "2.2 0 4"])
    elif kind == "tag":
        e = elements[rng.randrange(len(elements))]
        e[1] = rng.choice(["-1", "0", "255", "300", "70000", "99999999999"])
    elif kind == "short_element":
        e = elements[rng.choice(quad_rows)]
        del e[-1]
    elif kind == "merge_nodes":
        a, b = rng.sample(range(len(nodes)), 2)
        nodes[b][1:3] = nodes[a][1:3]
    elif kind == "scale":
        s = rng.choice([1e300, 1e-300, -1.0, 0.0, 1e155])
        for n in nodes:
            n[1], n[2] = repr(float(n[1]) * s), repr(float(n[2]) * s)
    elif kind == "duplicate_cell":
        elements.append(list(elements[rng.choice(quad_rows)]))
    elif kind == "unknown_type":
        elements[rng.randrange(len(elements))][0] = rng.choice(["99", "0", "-3", "x"])
    return kind, write_mesh(nodes, elements, **kw)


TOKENS = ["x", "y", "t", "1", "0", "2.5", "1e308", "1e-320", "+", "-", "*", "/", "^",
          "(", ")", ",", "=", ";", ":", "sin(", "sqrt(", "log(", "exp(", "abs(", "pi",
          "eps", "foo", "nx", "a", " ", "1/0", "x-0.5", "if(", "?", "<", "min(", "&"]


def random_expression(rng):
    """Half the cases a random token string (mostly a syntax error), half a well-formed
    expression that may not be finite somewhere (sqrt, log, division, exp of large
    values, huge constants)."""
    if rng.random() < 0.5:
        return "".join(rng.choice(TOKENS) for _ in range(rng.randint(1, 7)))

    def grow(depth):
        r = rng.random()
        if depth == 0 or r < 0.3:
            return rng.choice(["x", "y", "t", "1", "0", "0.5", "1e308", "1e-308", "pi",
                               "eps", "(x-0.5)", "(y-x)"])
        if r < 0.6:
            return grow(depth - 1) + rng.choice(["+", "-", "*", "/", "^"]) + grow(depth - 1)
        return rng.choice(["sqrt", "log", "exp", "sin", "abs", "tan"]) + "(" + grow(depth - 1) + ")"

    return grow(3)


def expression_case(rng):
    """(key, value): a random expression in one key of the custom scene."""
    key = rng.choice(["scene.rhs", "scene.initial_value", "scene.dirichlet",
                      "scene.convection", "scene.reaction"])
    e = random_expression(rng)
    if key == "scene.dirichlet":
        e = "0, 1, 2, 3: " + e
    elif key == "scene.convection":
        e = rng.choice([e + "; 0", "1; " + e, e])
    return key, e


BASE = {"scene": {"name": "custom", "epsilon": 0.01, "end_time": 1, "grid": "hyper_cube",
                  "grid_arguments": "0 : 1 : true", "convection": "1; 0", "reaction": "0",
                  "rhs": "1", "initial_value": "0", "dirichlet": "0, 1, 2, 3: 0",
                  "goals": "point 0.5, 0.5", "goals_over_time": True},
        "discretization": {"p": 1, "r": 0, "initial_refinements": 1, "n_slabs": 2},
        "study": {"mode": "dwr"}, "goal": {"kind": "scene"},
        "adaptivity": {"loops": 1}, "output": {"progress": False, "vtu_loops": 0}}


def run(binary, config, sets, out):
    cmd = [binary, "run", config, "--output", out]
    for s in sets:
        cmd += ["--set", s]
    try:
        p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                           timeout=20)
        return p.returncode, p.stdout.decode(errors="replace")
    except subprocess.TimeoutExpired:
        return "timeout", ""


def judge(rc, text, out, name):
    """None if the outcome is allowed, else what is wrong."""
    if rc == 0:
        try:
            status = json.load(open(os.path.join(out, "summary.json"))).get("status")
        except (OSError, ValueError):
            status = None
        return None if status == "ok" else f"exit 0 with summary status {status!r}"
    if rc == 2:
        return None if name in text else f"exit 2 without naming '{name}'"
    if rc == 3 and "numerical failure: loop" in text:
        return None  # data that are finite but overflow in the computation
    return f"exit {rc}"


def main():
    args = sys.argv[1:]
    binary, seed, cases = args[0], 20261202, 40
    if "--seed" in args:
        seed = int(args[args.index("--seed") + 1])
    if "--cases" in args:
        cases = int(args[args.index("--cases") + 1])
    rng = random.Random(seed)
    failures = 0
    with tempfile.TemporaryDirectory() as tmp:
        config = os.path.join(tmp, "base.json")
        with open(config, "w") as f:
            json.dump(BASE, f)
        kinds, codes = {}, {}
        for c in range(cases):
            kind, text = mutate_mesh(rng)
            mesh = os.path.join(tmp, f"m{c}.msh")
            with open(mesh, "w") as f:
                f.write(text)
            out = os.path.join(tmp, f"om{c}")
            rc, log = run(binary, config, [f"scene.mesh_file={mesh}",
                                           "scene.dirichlet=1, 2: 0"], out)
            kinds[kind] = kinds.get(kind, 0) + 1
            codes[rc] = codes.get(rc, 0) + 1
            bad = judge(rc, log, out, os.path.basename(mesh))
            if bad:
                failures += 1
                print(f"FAIL mesh case {c} ({kind}): {bad}\n{text}{log[-400:]}")
        for c in range(cases):
            key, value = expression_case(rng)
            out = os.path.join(tmp, f"oe{c}")
            rc, log = run(binary, config, [f"{key}={value}"], out)
            codes[rc] = codes.get(rc, 0) + 1
            bad = judge(rc, log, out, key)
            if bad:
                failures += 1
                print(f"FAIL expression case {c}: --set '{key}={value}': {bad}\n"
                      f"{log[-400:]}")
        print(f"{2 * cases} generated cases (seed {seed}; mesh mutations: "
              + ", ".join(f"{k} {v}" for k, v in sorted(kinds.items()))
              + "; exit codes: " + ", ".join(f"{k}: {v}" for k, v in sorted(codes.items(), key=str))
            + f"), {failures} failed")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
