#pragma once
/** @file config_include.h
 * `@include` for the project's INI files (doc/configuration.md "Includes and profiles").
 *
 * MRPT's INI format has no include. Its own preprocessing (mrpt::config, MRPT_IniFileParser,
 * run when a text is loaded into a CConfigFile or CConfigFileMemory) joins lines ending in `\`
 * and expands `@define NAME VALUE`, `${NAME}`, `$eval{...}` and `$env{...}`. An include has to
 * act before that, on files: readIniText() replaces every line `@include PATH` by the text of
 * PATH (recursively), so the result is one MRPT INI text, `@define`s of an included file
 * included. Rules:
 * - PATH is relative to the directory of the including file (or absolute);
 * - `@include` lines come before the including file's first section header, and no key may
 *   stand between them and that header (it would land in the included file's last section);
 * - a key set again later (in the including file, or in a later include) overrides the
 *   included one: MRPT's reader keeps the last value of a repeated key of a section;
 * - errors are std::runtime_error naming the file and line: a missing file, a circular include
 *   (with the chain), more than kMaxIncludeDepth nested includes, `@include` without a path or
 *   after a section header. */
#include <mrpt/config/CConfigFileMemory.h>

#include <string>
#include <vector>

namespace dynslam::config
{
/** Nested includes allowed below the top file (a profile that includes another is depth 2). */
constexpr int kMaxIncludeDepth = 8;

/** The text of the INI file `path` with its includes expanded (see the file comment).
 * `files` (if given) receives every file read, the top file first, in include order. */
std::string readIniText(const std::string& path, std::vector<std::string>* files = nullptr);

/** out.setContent(readIniText(path)): an app's INI with its includes. */
void loadIniWithIncludes(const std::string& path, mrpt::config::CConfigFileMemory& out,
                         std::vector<std::string>* files = nullptr);

/** A copy of `base` in which every key that the sections `sections` of the INI file `profile`
 * (read with its includes) set replaces the base's value in the same section: what a profile
 * changes in an app's INI (the model's core section and its module sections). Returns the keys
 * written, as "[section] key". Throws std::runtime_error naming the profile if its first
 * section is missing or empty (the others may be absent). */
std::vector<std::string> overlayProfile(const mrpt::config::CConfigFileMemory& base,
                                        const std::string& profile,
                                        const std::vector<std::string>& sections,
                                        mrpt::config::CConfigFileMemory& out);
}  // namespace dynslam::config
