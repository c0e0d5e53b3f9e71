# 64-bit Arm boards (Raspberry Pi 3/4/5 with a 64-bit OS, most Mali boards):
#   cmake -S . -B build-aarch64 -DCMAKE_TOOLCHAIN_FILE=toolchains/aarch64-linux-gnu.cmake [-DJADE_SYSROOT=...]
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(JADE_TRIPLE aarch64-linux-gnu)
set(JADE_QEMU_ARCH aarch64)
include(${CMAKE_CURRENT_LIST_DIR}/linux-cross.cmake)
