# Cross build for 64-bit ARM: Raspberry Pi 4/5 under Raspberry Pi OS (Debian 12 arm64), built on a
# Debian 12 amd64 machine with Debian's cross compilers (crossbuild-essential-arm64) and the
# libraries' :arm64 -dev packages installed beside the native ones (multiarch).
# install/cross-build-arm64.sh makes such a machine as a chroot and builds the .deb in it:
#   cmake -S . -B build-arm64 -DCMAKE_TOOLCHAIN_FILE=cmake/toolchain-aarch64-linux-gnu.cmake
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)

# Multiarch keeps the arm64 libraries in the same root as the build machine's, under
# /usr/lib/aarch64-linux-gnu (headers: /usr/include and /usr/include/aarch64-linux-gnu), so there is
# no separate sysroot to re-root the searches into: the root is the find root. The library
# architecture (which CMake also reads from the compiler) makes find_library, find_package and
# FindOpenCVLean look in aarch64-linux-gnu's folders; programs the build runs (espeak-ng, gzip)
# are the build machine's.
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)
set(CMAKE_FIND_ROOT_PATH /)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

# Debian 12's pkg-config (pkgconf) has no aarch64-linux-gnu-pkg-config wrapper that installs beside
# the native one, so the native one reads only arm64's .pc files (and the architecture-independent
# ones): a library missing as :arm64 then fails at configure time instead of linking amd64 flags.
# The toolchain file is read at every configure, so the setting holds for re-runs too.
set(ENV{PKG_CONFIG_LIBDIR} "/usr/lib/aarch64-linux-gnu/pkgconfig:/usr/share/pkgconfig")
unset(ENV{PKG_CONFIG_PATH})

# The build runs one of its own programs: cue_maker speaks the spoken cues at build time
# (textures/CMakeLists.txt). CMake puts the emulator in front of every custom command that runs a
# target of the project, so it runs as arm64 code under qemu-user (Debian's qemu-user-static; no
# binfmt registration is needed), loading its libraries from the multiarch folders; the espeak-ng
# it starts is the build machine's own.
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-aarch64-static)

# The .deb's architecture: CPack would otherwise ask dpkg, which names the build machine's
# (install/CMakeLists.txt also points dpkg-shlibdeps at arm64 with it).
set(CPACK_DEBIAN_PACKAGE_ARCHITECTURE arm64)
