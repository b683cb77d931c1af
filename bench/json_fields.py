#!/usr/bin/env python3
"""Prints fields of the JSON object on stdin, as the bench scripts read our tools' --json reports.

    json_fields.py [--tab] KEY ...

KEY is a field name or a dotted path into nested objects (seconds.encode). The values are printed on one
line, separated by spaces (by tabs with --tab), in the order given. A missing key is an error.
"""
import json
import sys


def field(document, path):
    value = document
    for key in path.split("."):
        value = value[key]
    return str(value)


def main(arguments):
    separator = " "
    if arguments and arguments[0] == "--tab":
        separator, arguments = "\t", arguments[1:]
    if not arguments:
        sys.exit("json_fields.py: expected at least one KEY")
    document = json.loads(sys.stdin.read())
    try:
        print(separator.join(field(document, key) for key in arguments))
    except (KeyError, TypeError) as error:
        sys.exit(f"json_fields.py: no field {error} in the report")


if __name__ == "__main__":
    main(sys.argv[1:])
