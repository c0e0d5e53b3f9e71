#!/bin/sh
# Prints, space-separated, the Debian packages among the arguments that are
# not installed (architecture-qualified names like libfoo:arm64 work).
for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || printf ' %s' "$p"
done
