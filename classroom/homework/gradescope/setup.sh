#!/usr/bin/env bash
# Gradescope's autograder image (Ubuntu): what the grader needs to compile a student's bdpt.cpp.
set -euo pipefail
apt-get update -qq
DEBIAN_FRONTEND=noninteractive apt-get install -y -qq g++ libstb-dev python3 >/dev/null
