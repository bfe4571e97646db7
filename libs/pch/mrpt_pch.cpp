// The translation unit that builds the shared MRPT precompiled header (libs/pch/CMakeLists.txt).
