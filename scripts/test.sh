#!/usr/bin/env bash
# Runs every lumlab test, as CI does. On a fresh Debian machine it first
# installs what the tests need: Mesa's software Vulkan driver (lavapipe, the
# GPU of machines without one), its GL one through EGL (llvmpipe, the lab's
# fallback), Xvfb (for the window test) and a C++ compiler.
set -euo pipefail
cd "$(dirname "$0")/.."

need=()
ldconfig -p 2>/dev/null | grep -q 'libvulkan.so.1' || need+=(libvulkan1)
ls /usr/share/vulkan/icd.d/lvp_icd*.json >/dev/null 2>&1 || need+=(mesa-vulkan-drivers)
ldconfig -p 2>/dev/null | grep -q 'libEGL.so.1' || need+=(libegl1)
ls /usr/share/glvnd/egl_vendor.d/*mesa*.json >/dev/null 2>&1 || need+=(libegl-mesa0)
ls /usr/lib/*/dri/swrast_dri.so >/dev/null 2>&1 || need+=(libgl1-mesa-dri)
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

# The whole suite (no arguments, no backend chosen) then runs the tests that
# draw through the renderer again on GL, where texture kinds, layer counts,
# formats and depth arithmetic differ from Vulkan (docs/DESIGN.md): the
# fallback stays tested. `WGPU_BACKEND=gl bash scripts/test.sh` runs all of
# them there.
if [ $# -eq 0 ] && [ -z "${WGPU_BACKEND:-}" ]; then
  gl_tests=(cube_seams delta_e_view depth_precision depth_ranges gpu_bvh gpu_raytrace gpu_renderer
    gpu_visibility_sources reference_gpu specialised_shading split_view wgsl_parity)
  echo "again on GL (llvmpipe): ${gl_tests[*]}"
  WGPU_BACKEND=gl cargo test --locked "${gl_tests[@]/#/--test=}"
fi
