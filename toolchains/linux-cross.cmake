# Shared body of jade's cross toolchain files; the per-target files set
# JADE_TRIPLE and CMAKE_SYSTEM_PROCESSOR, then include this.
#
# Two ways to use them:
#   Debian multiarch: dpkg --add-architecture arm64, the :arm64 -dev packages
#     and crossbuild-essential-arm64 (tools/setup-cross.sh does it); no sysroot.
#   A board sysroot (Yocto SDK, a mounted Raspberry Pi OS image):
#     -DJADE_SYSROOT=/path/to/sysroot (or the JADE_SYSROOT environment variable).
set(CMAKE_SYSTEM_NAME Linux)

if(NOT JADE_SYSROOT AND DEFINED ENV{JADE_SYSROOT})
  set(JADE_SYSROOT "$ENV{JADE_SYSROOT}")
endif()
set(JADE_SYSROOT "${JADE_SYSROOT}" CACHE PATH "target sysroot (empty: Debian multiarch)")
# Try-compile projects re-read this file: pass the choice on.
list(APPEND CMAKE_TRY_COMPILE_PLATFORM_VARIABLES JADE_SYSROOT)

# Compilers: <triple>-gcc unless the caller chose (a Yocto SDK sets CC).
if(NOT CMAKE_C_COMPILER)
  set(CMAKE_C_COMPILER ${JADE_TRIPLE}-gcc)
endif()
if(NOT CMAKE_CXX_COMPILER)
  set(CMAKE_CXX_COMPILER ${JADE_TRIPLE}-g++)
endif()
set(CMAKE_LIBRARY_ARCHITECTURE ${JADE_TRIPLE})

if(JADE_SYSROOT)
  set(CMAKE_SYSROOT "${JADE_SYSROOT}")
  set(CMAKE_FIND_ROOT_PATH "${JADE_SYSROOT}")
  set(ENV{PKG_CONFIG_SYSROOT_DIR} "${JADE_SYSROOT}")
  set(ENV{PKG_CONFIG_LIBDIR}
      "${JADE_SYSROOT}/usr/lib/${JADE_TRIPLE}/pkgconfig:${JADE_SYSROOT}/usr/lib/pkgconfig:${JADE_SYSROOT}/usr/share/pkgconfig")
else()
  # Multiarch: target libraries live beside the host's, under /usr/lib/<triple>.
  set(CMAKE_FIND_ROOT_PATH "/usr/${JADE_TRIPLE}" "/")
  set(ENV{PKG_CONFIG_SYSROOT_DIR} "")
  set(ENV{PKG_CONFIG_LIBDIR} "/usr/lib/${JADE_TRIPLE}/pkgconfig:/usr/share/pkgconfig")
endif()

# Programs run on the build machine; everything else comes from the target.
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

# Tests built for the target run under qemu-user when it is installed.
find_program(JADE_QEMU qemu-${JADE_QEMU_ARCH})
if(JADE_QEMU)
  if(JADE_SYSROOT)
    set(CMAKE_CROSSCOMPILING_EMULATOR ${JADE_QEMU} -L ${JADE_SYSROOT})
  else()
    set(CMAKE_CROSSCOMPILING_EMULATOR ${JADE_QEMU})
  endif()
endif()
