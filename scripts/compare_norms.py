#!/usr/bin/env python3
"""Compares the error norms of two `radrecon paper` runs (errors.json files).

Usage: compare_norms.py EXPECTED.json ACTUAL.json [--rel-tol T]

Every norm of every table ("grid", "quadtree", and any other table both files have) is compared.
Exit 0 when all agree within the relative tolerance (default 0: bit for bit), 1 otherwise; the
report says whether the runs are bit-identical and lists every difference.
"""
import json
import sys


def main(argv):
    args = [a for a in argv[1:] if not a.startswith("--")]
    rel_tol = 0.0
    if "--rel-tol" in argv:
        rel_tol = float(argv[argv.index("--rel-tol") + 1])
        args.remove(argv[argv.index("--rel-tol") + 1])
    if len(args) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    expected, actual = (json.load(open(path)) for path in args)
    compared, identical, failures = 0, 0, []
    for table, methods in expected.items():
        if not isinstance(methods, dict) or table == "settings":
            continue
        for method, norms in methods.items():
            if not isinstance(norms, dict):
                continue
            for norm, want in norms.items():
                got = actual.get(table, {}).get(method, {}).get(norm)
                compared += 1
                if got == want:
                    identical += 1
                    continue
                rel = abs(got - want) / max(abs(want), 1e-300) if got is not None else float("inf")
                if rel > rel_tol:
                    failures.append(f"{table}/{method}/{norm}: expected {want!r}, got {got!r} (relative {rel:.3g})")
    print(f"compare_norms: {compared} norms, {identical} bit-identical"
          + ("" if identical == compared else f", {compared - identical} differ (tolerance {rel_tol:g})"))
    for f in failures:
        print("  " + f)
    return 1 if failures or compared == 0 else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
