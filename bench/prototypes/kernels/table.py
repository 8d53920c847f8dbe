"""Joins the firmware's region labels (1-based) with the plugin's exact counts: label, instructions,
instructions a pixel, estimated M4 cycles a pixel. Usage: python3 table.py run-m4.log. The plugin numbers regions from 0."""
import re, sys
labels, exact = {}, {}
for line in open(sys.argv[1]):
    m = re.match(r"region (\d+): (.*) \| px=(\d+) \|", line)
    if m:
        labels[int(m.group(1))] = (m.group(2), int(m.group(3)))
        continue
    m = re.match(r"region (\d+): insns=(\d+) est_m4_cycles=(\d+) loads=(\d+) stores=(\d+) taken_branches=(\d+)", line)
    if m:
        exact[int(m.group(1)) + 1] = tuple(int(x) for x in m.groups()[1:])
    elif not line.startswith("region"):
        if line.strip() and not line.startswith("total"):
            print("#", line.rstrip())
# Span regions: also net of the harness (the same row loop calling an empty function).
base = {}
for r, (name, px) in labels.items():
    if name.startswith("baseline"):
        base[name.split(", ", 1)[1]] = exact.get(r, (0,))[0]
for r in sorted(labels):
    name, px = labels[r]
    ins, cyc, ld, st, tk = exact.get(r, (0, 0, 0, 0, 0))
    case = name.split(", ")[-1]
    net = f"  net {(ins - base[case]) / px:6.3f}/px" if case in base and not name.startswith("baseline") else ""
    print(f"{r:3d} {name:<62s} {ins:>9d} insns  {ins/px:6.3f}/px  ~{cyc/px:6.3f} cyc/px{net}")
