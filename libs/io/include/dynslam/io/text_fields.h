#pragma once
/** @file text_fields.h
 * Strict parsing of whitespace-separated text files (the dataset readers of MRCLAM, KITTI and
 * the ground-truth files): every error names the file and the 1-based line. */
#include <cstddef>
#include <string>
#include <vector>

namespace dynslam::io
{
/** Throws std::runtime_error("path:line: what"). */
[[noreturn]] void throwAtLine(const std::string& path, int line, const std::string& what);

/** The whitespace-separated tokens of a line. */
std::vector<std::string> splitWhitespace(const std::string& s);

/** Token `tok` of column `col` (0-based) as a finite double; throws naming path, line and the
 * 1-based column when it does not parse completely or is not finite. */
double parseFiniteField(const std::string& tok, const std::string& path, int line, size_t col);
}  // namespace dynslam::io
