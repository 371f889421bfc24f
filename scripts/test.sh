#!/usr/bin/env bash
# Runs every lumlab test, as CI does. On a fresh Debian machine it first
# installs what the tests need: Mesa's software Vulkan driver (lavapipe, the
# GPU of machines without one), Xvfb (for the window test) and a C++ compiler.
set -euo pipefail
cd "$(dirname "$0")/.."

need=()
ldconfig -p 2>/dev/null | grep -q 'libvulkan.so.1' || need+=(libvulkan1)
ls /usr/share/vulkan/icd.d/lvp_icd*.json >/dev/null 2>&1 || need+=(mesa-vulkan-drivers)
command -v xvfb-run >/dev/null 2>&1 || need+=(xvfb)
# meshoptimizer (the drag frames' simplified meshes) is C++, built by the meshopt crate.
command -v c++ >/dev/null 2>&1 || need+=(g++)
if [ ${#need[@]} -gt 0 ]; then
  echo "installing: ${need[*]}"
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${need[@]}"
fi

# lavapipe wants a private runtime directory; without one it only complains.
if [ -z "${XDG_RUNTIME_DIR:-}" ] || [ ! -d "$XDG_RUNTIME_DIR" ]; then
  XDG_RUNTIME_DIR="$(mktemp -d)"
  chmod 700 "$XDG_RUNTIME_DIR"
  export XDG_RUNTIME_DIR
fi

# Under WGPU_BACKEND=gl (Mesa's llvmpipe) the tests render to f32 targets as
# the lumlab binary does (src/gpu/context.rs: mesa_extension_override);
# Vulkan ignores it.
export MESA_EXTENSION_OVERRIDE="${MESA_EXTENSION_OVERRIDE:-+GL_ARB_color_buffer_float}"

cargo test --locked "$@"
