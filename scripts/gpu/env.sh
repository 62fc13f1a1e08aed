# Sourced on the GPU machine, from the project root, in place of ../shared/gpu/unpack.sh (docs/performance.md, "The
# WebGPU solver"): node and Dawn from .gpu/ (made by ../shared/gpu/pack.sh on the build machine), and the NVIDIA
# Vulkan driver through EGL. On the H100 machine of 2026-12-05 (driver 580.159.04, no X server) the driver's own
# manifest names libGLX_nvidia.so.0, which loads but gives the Vulkan loader no vkCreateInstance, so Dawn found no
# adapter; the same driver through libEGL_nvidia.so.0 (scripts/gpu/nvidia-egl-icd.json) works. The Vulkan loader is
# .gpu/vk14's when present (Debian trixie's libvulkan1 1.4.309, unpacked there on the build machine: the run that
# worked used it), else the bundle's (bookworm's 1.3.239, not yet tried with the EGL manifest).
[ -x /tmp/gpu/bin/node ] || { mkdir -p /tmp/gpu/bin && xz -dc .gpu/node.xz > /tmp/gpu/bin/node && chmod +x /tmp/gpu/bin/node; }
[ -f node_modules/webgpu/package.json ] || { mkdir -p node_modules/webgpu && xz -dc .gpu/webgpu.tar.xz | tar -xf - -C node_modules/webgpu; }
export PATH=/tmp/gpu/bin:$PATH
if [ -f .gpu/vk14/libvulkan.so.1 ]; then
  export LD_LIBRARY_PATH=$PWD/.gpu/vk14${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
elif ! ldconfig -p | grep -q libvulkan.so.1; then
  mkdir -p /tmp/gpu/vk && dpkg -x .gpu/libvulkan1_*.deb /tmp/gpu/vk
  export LD_LIBRARY_PATH=/tmp/gpu/vk/usr/lib/x86_64-linux-gnu${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
fi
export VK_DRIVER_FILES=$PWD/scripts/gpu/nvidia-egl-icd.json
node scripts/gpu/adapter.cjs
