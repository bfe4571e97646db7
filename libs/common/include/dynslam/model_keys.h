#pragma once
/** @file model_keys.h
 * The descriptor table of section [DynamicKFSLAM]: every key with its type, default, unit and
 * a one-line description. It is the list of known keys (TModelOptions::loadFromConfigFile
 * rejects any other), the source of doc/configuration.md (writeKeyReference; the test
 * ConfigDoc.CommittedReferenceIsCurrent fails when the committed file is stale) and, through
 * ConfigDoc.DescriptorDefaultsAreTheDumpedDefaults, checked against the defaults that
 * TModelOptions::dumpToTextStream prints. */
#include <iosfwd>
#include <string>
#include <vector>

namespace dynslam
{
struct TKeyInfo
{
	std::string key;
	std::string type;        ///< e.g. "real", "int >= 0", "bool", "cartesian | range_bearing"
	std::string def;         ///< the default as dumpToTextStream prints it; "required" if none
	std::string unit;        ///< "-" if none
	std::string what;        ///< one line
	std::string capability;  ///< the group it belongs to (a heading of the reference)
};

/** Every key of [DynamicKFSLAM], in the order of the reference. */
const std::vector<TKeyInfo>& modelKeys();

/** The names of modelKeys(). */
std::vector<std::string> modelKeyNames();

/** A profile and the [DynamicKFSLAM] keys it sets (with their values). */
struct TProfileKeys
{
	std::string name;  ///< e.g. "paper" (config/profiles/paper.ini)
	std::vector<std::pair<std::string, std::string>> keys;
};

/** Writes the markdown key reference (doc/configuration.md's generated part) to `out`:
 * one table per capability, the column "profiles" from `profiles`. */
void writeKeyReference(std::ostream& out, const std::vector<TProfileKeys>& profiles);
}  // namespace dynslam
