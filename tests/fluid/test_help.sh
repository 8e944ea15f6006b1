#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# fluid-app -help: exit status 0 and every option listed, the fsi::comm flags included.
# usage: test_help.sh FLUID_APP
app=$1
out=$("$app" -help 2>&1)
rc=$?
if [ "$rc" -ne 0 ]; then
  echo "fluid-app -help: exit status $rc (expected 0)"; echo "$out"; exit 1
fi
for option in --launch --port-file --comm-timeout -restart -rigid -coupled -prescribed -case -parallel; do
  if ! printf '%s\n' "$out" | grep -q -- "$option"; then
    echo "fluid-app -help: option $option not listed"; echo "$out"; exit 1
  fi
done
echo "fluid-app -help: exit 0, every option listed"
