#!/usr/bin/python3
"""Table of run_message_counts.sh: per rank count, the decomposition's traffic per step, summed over
the ranks and per rank (the sum over the ranks divided by them), and the particles per rank.
Prints Markdown.
    message_counts.py message_counts.csv
"""
import csv
import sys

rows = [r for r in csv.DictReader(open(sys.argv[1])) if r["status"] == "completed"]
print(f"Example 2 at grid.spacing = {rows[0]['spacing']}: the {rows[0]['steps']} steps up to "
      f"t = {rows[0]['end_time_s']} s (after a start run on the same ranks when the script's START was given). "
      "Oversubscribed runs: the counts are what a cluster's run sends, the times are not.")
print()
print("| ranks | particles per rank (min-max) | halo MB/step (all ranks) | halo kB/step per rank | halo messages/step "
      "per rank | migration kB/step per rank | migration messages/step per rank |")
print("| --- | --- | --- | --- | --- | --- | --- |")
for r in sorted(rows, key=lambda r: int(r["ranks"])):
    p = int(r["ranks"])
    per_rank = [int(x) for x in r["particles_per_rank"].split()]
    halo = float(r["halo_bytes_per_step"])
    print(f"| {p} | {min(per_rank)}-{max(per_rank)} | {halo / 1e6:.2f} | {halo / p / 1e3:.0f} | "
          f"{float(r['halo_messages_per_step']) / p:.1f} | {float(r['migration_bytes_per_step']) / p / 1e3:.1f} | "
          f"{float(r['migration_messages_per_step']) / p:.2f} |")
