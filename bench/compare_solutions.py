#!/usr/bin/env python3
"""Relative differences of a solution's radiosity (channels summed) from a reference solution of
the same mesh, per surface side: elements brighter than 1e-3 of the side's peak; on a side named
"ground", also its umbra (below 15% of its peak). Usage: compare_solutions.py SOLUTION REFERENCE"""
import json
import sys


def radiosities(path):
    with open(path) as f:
        return {s["name"]: [sum(e["radiosity"]) for e in s["elements"]] for s in json.load(f)["surfaces"]}


def main():
    got, ref = radiosities(sys.argv[1]), radiosities(sys.argv[2])
    worst = 0.0
    for name, r in ref.items():
        peak = max(r)
        if peak <= 0 or name == "light":
            continue
        rel = [(a - b) / b for a, b in zip(got[name], r) if b > 1e-3 * peak]
        worst = max(worst, max(abs(x) for x in rel))
        line = f"  {name:16s} mean {sum(rel) / len(rel):+.4f}  largest |rel| {max(abs(x) for x in rel):.4f}"
        if name == "ground":
            umbra = [(a - b) / b for a, b in zip(got[name], r) if 0 < b < 0.15 * peak]
            if umbra:
                line += f"  umbra mean {sum(umbra) / len(umbra):+.4f} largest {max(abs(x) for x in umbra):.4f}"
        print(line)
    print(f"  worst {worst:.4f}")


if __name__ == "__main__":
    main()
