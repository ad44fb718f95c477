#!/usr/bin/env python3
"""Writes a system file of a chain of N bodies for measuring how fast files load.

    python3 scripts/chain-file.py N OUT.toml [--contact-every K] [--inline]
    python3 scripts/chain-file.py N OUT.json [--contact-every K]

An anchor `d` driven at 0.1 m/s, N bodies `b1`..`bN` of 1 kg, springs from the anchor to b1
and between neighbours, and a Coulomb contact on every K-th body (default every body). 10⁶ bodies with a contact on
every tenth: 77 MB of `[[table]]`s. `--inline` writes the tables as inline arrays instead
(62 MB), which a TOML file may hold up to 32 MiB of. A name ending `.json` writes the same
system as JSON (68 MB). docs/performance.md, "Loading a system file".
"""
import argparse

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("n", type=int)
parser.add_argument("out")
parser.add_argument("--contact-every", type=int, default=1)
parser.add_argument("--inline", action="store_true")
args = parser.parse_args()
n, every = args.n, args.contact_every
# Each row as its key = value pairs.
bodies = [(f'name="b{i}"', "m=1") for i in range(1, n + 1)]
springs = [('between=["d","b1"]', "k=10")] + [
    (f'between=["b{i}","b{i + 1}"]', "k=9") for i in range(1, n)]
contacts = [(f'body="b{i}"', 'model="coulomb"') for i in range(1, n + 1, every)]
if args.out.endswith(".json"):
    import json

    def table(rows):
        return [json.loads("{" + ",".join(
            '"{}":{}'.format(*kv.split("=", 1)) for kv in row) + "}") for row in rows]

    system = {"anchor": [{"name": "d", "v": 0.1}], "body": table(bodies),
              "spring": table(springs), "contact": table(contacts)}
    with open(args.out, "w") as f:
        json.dump(system, f, separators=(",", ":"))
    raise SystemExit
with open(args.out, "w") as f:
    # Top-level keys come before any [[table]] header: inline, the anchor is an array too.
    f.write('anchor=[{name="d",v=0.1}]\n' if args.inline else '[[anchor]]\nname="d"\nv=0.1\n')
    for table, rows in (("body", bodies), ("spring", springs), ("contact", contacts)):
        if args.inline:
            f.write(f"{table}=[\n" + ",\n".join("{" + ",".join(r) + "}" for r in rows) + "]\n")
        else:
            f.write("".join(f"[[{table}]]\n" + "\n".join(r) + "\n" for r in rows))
