#!/usr/bin/env bash
# deps.sh - install the Debian packages lanetrace needs, idempotently (make deps).
# Skips what is present; as root runs apt-get, otherwise prints the exact command to run.
set -euo pipefail
PKGS=(gcc make pkg-config gcc-arm-none-eabi libnewlib-arm-none-eabi gcc-riscv64-unknown-elf
      qemu-system-arm qemu-system-misc libcmocka-dev libcjson-dev libassimp-dev
      libopenexr-dev libpng-dev zlib1g-dev libembree-dev libhidapi-dev gnuplot-nox clang
      libclang-rt-14-dev
      assimp-testmodels chromium parallel python3)
missing=()
for p in "${PKGS[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
        missing+=("$p")
    fi
done
if [ ${#missing[@]} -eq 0 ]; then
    echo "deps: all ${#PKGS[@]} packages present"
    exit 0
fi
cmd="apt-get install -y --no-install-recommends ${missing[*]}"
if [ "$(id -u)" -ne 0 ]; then
    echo "deps: missing ${missing[*]}; run as root:"
    echo "  apt-get update && $cmd"
    exit 1
fi
echo "deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
# shellcheck disable=SC2086
$cmd
