#!/usr/bin/env python3
"""Writes a CENG795 XML scene in the course's JSON form (shared/formats/ceng795-later.md, section 15):
an element is a key; its attributes are "_name" keys and its text "_data" when it has attributes;
an element with only text is a string; an element repeated under one parent is an array. Used to
make the json_scene harness's seeds from the xml_scene ones (a PLY part after the line
"==> mesh.ply <==" is copied as it is):

    tests/fuzz/xml_to_course_json.py IN.xml > OUT.json
"""
import json
import sys
import xml.etree.ElementTree as ET


def convert(el):
    children = list(el)
    text = " ".join((el.text or "").split() + [w for c in children for w in (c.tail or "").split()])
    if not el.attrib and not children:
        return text
    out = {"_" + k: v for k, v in el.attrib.items()}
    if text:
        out["_data"] = text
    for c in children:
        value = convert(c)
        if c.tag in out:
            if not isinstance(out[c.tag], list):
                out[c.tag] = [out[c.tag]]
            out[c.tag].append(value)
        else:
            out[c.tag] = value
    return out


data = open(sys.argv[1], "rb").read()
marker = b"\n==> mesh.ply <==\n"
xml, found, ply = data.partition(marker)
root = ET.fromstring(xml)
out = sys.stdout.buffer
out.write(json.dumps({root.tag: convert(root)}, indent=1).encode() + b"\n")
if found:
    out.write(marker[1:] + ply)
