# 32-bit Arm with hardware float (Raspberry Pi OS 32-bit, Mali-400 boards):
#   cmake -S . -B build-armhf -DCMAKE_TOOLCHAIN_FILE=toolchains/arm-linux-gnueabihf.cmake [-DJADE_SYSROOT=...]
set(CMAKE_SYSTEM_PROCESSOR arm)
set(JADE_TRIPLE arm-linux-gnueabihf)
set(JADE_QEMU_ARCH arm)
include(${CMAKE_CURRENT_LIST_DIR}/linux-cross.cmake)
