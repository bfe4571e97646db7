#pragma once
/** @file registry.h
 * One registry per seam (doc/architecture.md, "Seams and their registries"): the INI name of
 * each implementation -> its factory and its capabilities. The one place where an
 * implementation's name is looked up: code that needs to know what an implementation does asks
 * its capabilities (or the instance), never compares its name. */
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace dynslam::estimator
{
template <class Product, class Params, class Caps>
class CRegistry
{
public:
	using Factory = std::function<std::unique_ptr<Product>(const Params&)>;

	/** key: the INI key that names an implementation (for the error messages). */
	explicit CRegistry(std::string key) : m_key(std::move(key)) {}

	/** Registers `name`; throws std::logic_error if it is taken or the factory is empty. */
	void add(const std::string& name, Factory make, Caps caps)
	{
		if (has(name) || !make)
			throw std::logic_error(m_key + " = " + name + ": registered twice or without factory");
		m_entries.push_back({name, {std::move(make), std::move(caps)}});
	}
	bool has(const std::string& name) const { return find(name) != nullptr; }
	/** Throws std::invalid_argument naming the key, the value and the known names. */
	const Caps& caps(const std::string& name) const { return get(name).caps; }
	std::unique_ptr<Product> make(const std::string& name, const Params& p) const
	{
		return get(name).make(p);
	}
	/** The names in registration order. */
	std::vector<std::string> names() const
	{
		std::vector<std::string> out;
		for (const auto& e : m_entries) out.push_back(e.first);
		return out;
	}
	const std::string& key() const { return m_key; }

private:
	struct TEntry
	{
		Factory make;
		Caps caps;
	};
	const TEntry* find(const std::string& name) const
	{
		for (const auto& e : m_entries)
			if (e.first == name) return &e.second;
		return nullptr;
	}
	const TEntry& get(const std::string& name) const
	{
		if (const TEntry* e = find(name)) return *e;
		std::string known;
		for (const auto& e : m_entries) known += (known.empty() ? "" : ", ") + e.first;
		throw std::invalid_argument(m_key + " = " + name + ": unknown (known: " + known + ")");
	}
	std::string m_key;
	std::vector<std::pair<std::string, TEntry>> m_entries;
};
}  // namespace dynslam::estimator
