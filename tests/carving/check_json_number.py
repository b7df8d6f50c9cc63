#!/usr/bin/python3
"""A number in a JSON file within TOLERANCE (relative) of EXPECTED.
    check_json_number.py FILE KEY EXPECTED TOLERANCE
"""
import json
import sys

path, key, expected, tolerance = sys.argv[1], sys.argv[2], float(sys.argv[3]), float(sys.argv[4])
value = float(json.load(open(path))[key])
error = value / expected - 1
print(f"{key}: {value:.6g} against {expected:.6g} ({100 * error:+.3f}%)")
assert abs(error) <= tolerance, f"{key} off by {error:+.4%}, beyond {tolerance:.2%}"
