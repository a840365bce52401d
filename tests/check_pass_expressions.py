#!/usr/bin/python3
"""A test's PASS_REGULAR_EXPRESSION must be one expression: CMake splits a property's value at each ';'
into a list, and CTest passes a test when any one of the pieces matches, so an expression with a ';'
in it quietly asks for less than it says. Writes each offending line and exits 1; usage:
check_pass_expressions.py FILE...
"""
import re
import sys

bad = 0
for path in sys.argv[1:]:
    text = open(path).read()
    for m in re.finditer(r'PASS_REGULAR_EXPRESSION\s+"((?:[^"\\]|\\.)*)"', text):
        if ";" in m.group(1):
            line = text.count("\n", 0, m.start()) + 1
            print(f"{path}:{line}: a ';' splits this PASS_REGULAR_EXPRESSION into alternatives: {m.group(1)[:100]}")
            bad += 1
print(f"{bad} expressions split" if bad else "every PASS_REGULAR_EXPRESSION is one expression")
sys.exit(1 if bad else 0)
