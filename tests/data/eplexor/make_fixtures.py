#!/usr/bin/env python3
"""Malformed EPLEXOR fixture: datasets/materials/pyvisco-eplexor-raw.xls with the storage modulus
of spreadsheet row 4 (E' = 8576.84..., column M of 'Exported Data') negated in place. The double
occurs once in the file, so the patch changes exactly that cell. Run from the repository root."""
import struct

src = open("datasets/materials/pyvisco-eplexor-raw.xls", "rb").read()
old = struct.pack("<d", 8576.8438245957914)
assert src.count(old) == 1
open("tests/data/eplexor/negative_storage.xls", "wb").write(src.replace(old, struct.pack("<d", -8576.8438245957914)))
