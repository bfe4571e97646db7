/** @file class_ground_truth.cpp
 * B_gt_classes.csv: writer and strict reader (see class_ground_truth.h). */
#include <dynslam/io/class_ground_truth.h>
#include <dynslam/io/number_format.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace dynslam::io
{
namespace
{
const char* kHeader = "step,t,index,id,true_id,class,object,feature";

[[noreturn]] void fail(const std::string& path, size_t line, const std::string& what)
{
	throw std::runtime_error(path + ":" + std::to_string(line) + ": " + what);
}

long toLong(const std::string& s, const std::string& path, size_t line, const char* col)
{
	char* e = nullptr;
	const long v = std::strtol(s.c_str(), &e, 10);
	if (s.empty() || *e != '\0')
		fail(path, line, std::string(col) + " '" + s + "' is not an integer");
	return v;
}
}  // namespace

const char* toString(TrueClass c)
{
	switch (c)
	{
		case TrueClass::Static:
			return "static";
		case TrueClass::Moving:
			return "moving";
		default:
			return "clutter";
	}
}

void writeClassGroundTruth(const std::vector<TReadingClass>& rows, const std::string& path)
{
	std::ofstream f(path, std::ios::binary);
	if (!f) throw std::runtime_error("writeClassGroundTruth: cannot write " + path);
	f << kHeader << "\n";
	for (const TReadingClass& r : rows)
		f << r.step << "," << formatShortest(r.t) << "," << r.index << "," << r.id << ","
		  << r.true_id << "," << toString(r.cls) << "," << r.object << "," << r.feature << "\n";
	f.close();
	if (!f) throw std::runtime_error("writeClassGroundTruth: error writing " + path);
}

std::vector<TReadingClass> readClassGroundTruth(const std::string& path)
{
	std::ifstream in(path, std::ios::binary);
	if (!in) throw std::runtime_error("readClassGroundTruth: cannot open " + path);
	std::string line;
	if (!std::getline(in, line) || line != kHeader)
		fail(path, 1, std::string("expected the header '") + kHeader + "'");
	std::vector<TReadingClass> rows;
	for (size_t ln = 2; std::getline(in, line); ++ln)
	{
		if (line.empty()) continue;
		std::vector<std::string> c;
		std::stringstream ss(line);
		for (std::string tok; std::getline(ss, tok, ',');) c.push_back(tok);
		if (c.size() != 8) fail(path, ln, "expected 8 columns, got " + std::to_string(c.size()));
		TReadingClass r;
		r.step = int(toLong(c[0], path, ln, "step"));
		char* e = nullptr;
		r.t = std::strtod(c[1].c_str(), &e);
		if (c[1].empty() || *e != '\0' || !std::isfinite(r.t))
			fail(path, ln, "t '" + c[1] + "' is not a finite number");
		r.index = int(toLong(c[2], path, ln, "index"));
		r.id = int32_t(toLong(c[3], path, ln, "id"));
		r.true_id = int32_t(toLong(c[4], path, ln, "true_id"));
		if (c[5] == "static")
			r.cls = TrueClass::Static;
		else if (c[5] == "moving")
			r.cls = TrueClass::Moving;
		else if (c[5] == "clutter")
			r.cls = TrueClass::Clutter;
		else
			fail(path, ln, "unknown class '" + c[5] + "' (expected static, moving or clutter)");
		r.object = int32_t(toLong(c[6], path, ln, "object"));
		r.feature = int32_t(toLong(c[7], path, ln, "feature"));
		if (r.step < 0 || r.index < 0) fail(path, ln, "negative step or index");
		if (r.cls == TrueClass::Clutter && (r.true_id != -1 || r.object != -1 || r.feature != -1))
			fail(path, ln, "a clutter reading has true_id, object and feature -1");
		if (r.cls == TrueClass::Moving && r.object < 0)
			fail(path, ln, "a moving reading needs its object");
		if (r.cls != TrueClass::Clutter && (r.true_id < 0 || r.feature < 0))
			fail(path, ln, "a static or moving reading needs true_id and feature >= 0");
		rows.push_back(r);
	}
	return rows;
}
}  // namespace dynslam::io
