#!/usr/bin/env bash
# Installs the Debian packages the build, tests and tools need. Idempotent; quiet when all
# is already there. Nothing is downloaded except Debian packages.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  clang clang-14 libclang-rt-14-dev clang-format clang-tidy
  googletest libgtest-dev libgmock-dev libbenchmark-dev
  libeigen3-dev libdxflib-dev libcli11-dev libfmt-dev libasio-dev nlohmann-json3-dev
  libcairo2-dev libexpat1-dev
  gcc-avr binutils-avr avr-libc simavr libsimavr-dev python3
  sigrok-cli socat zlib1g-dev curl jq
  libpolyclipping-dev gerbv
  libsqlite3-dev libcpp-httplib-dev chromium libpqxx-dev postgresql libzip-dev
)

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "bootstrap: installing ${missing[*]}" >&2
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
