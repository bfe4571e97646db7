#include <dynslam/eval/run_records.h>

#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

namespace dynslam::eval
{
namespace
{
std::string hx(double v)
{
	char b[48];
	std::snprintf(b, sizeof(b), "%a", v);
	return b;
}

void rmseLine(std::ostream& os, const std::string& name, const TRmse& r)
{
	os << "rmse " << name << ' ' << hx(r.x) << ' ' << hx(r.y) << ' ' << hx(r.theta) << ' ' << r.n_xy
	   << ' ' << r.n_theta << '\n';
}

void samplesLine(std::ostream& os, const std::string& name, const TNeesSamples& s)
{
	os << "samples " << name << ' ' << s.skipped_singular << ' ' << s.samples.size();
	for (const auto& x : s.samples) os << ' ' << x.key << ' ' << hx(x.value) << ' ' << x.dof;
	os << '\n';
}

/** Line-by-line reader with errors naming file and line. */
struct TReader
{
	std::istream& is;
	std::string name;
	int lineNo = 0;
	std::istringstream cur;
	std::string word;

	[[noreturn]] void fail(const std::string& what) const
	{
		throw std::runtime_error("run records '" + name + "', line " + std::to_string(lineNo) +
		                         ": " + what);
	}
	/** Next non-comment line; returns its first word ("" at end of file). */
	std::string next()
	{
		std::string l;
		while (std::getline(is, l))
		{
			++lineNo;
			if (l.empty() || l[0] == '#') continue;
			cur.clear();
			cur.str(l);
			cur >> word;
			return word;
		}
		word.clear();
		cur.clear();
		cur.str("");
		return {};
	}
	void expect(const std::string& w)
	{
		if (next() != w) fail("expected '" + w + "', found '" + word + "'");
	}
	std::string str()
	{
		std::string s;
		if (!(cur >> s)) fail("missing field");
		return s;
	}
	double dbl()
	{
		const std::string s = str();
		char* end = nullptr;
		const double v = std::strtod(s.c_str(), &end);
		if (end == s.c_str() || *end) fail("not a number: '" + s + "'");
		return v;
	}
	template <class T>
	T integer()
	{
		const std::string s = str();
		try
		{
			size_t pos = 0;
			const long long v = std::stoll(s, &pos);
			if (pos != s.size()) throw std::invalid_argument(s);
			return T(v);
		}
		catch (const std::exception&)
		{
			fail("not an integer: '" + s + "'");
		}
	}
	TRmse rmse(const std::string& nm)
	{
		expect("rmse");
		if (str() != nm) fail("expected rmse " + nm);
		TRmse r;
		r.x = dbl();
		r.y = dbl();
		r.theta = dbl();
		r.n_xy = integer<size_t>();
		r.n_theta = integer<size_t>();
		return r;
	}
	TNeesSamples samples(std::string& nm)
	{
		if (word != "samples") fail("expected 'samples', found '" + word + "'");
		nm = str();
		TNeesSamples s;
		s.skipped_singular = integer<size_t>();
		const size_t n = integer<size_t>();
		for (size_t i = 0; i < n; ++i)
		{
			TNeesSample x;
			x.key = integer<int>();
			x.value = dbl();
			x.dof = integer<int>();
			s.samples.push_back(x);
		}
		return s;
	}
};
}  // namespace

void writeRunRecords(std::ostream& os, const TRunRecordFile& f)
{
	os << "# dynslam-montecarlo per-run records (libs/eval/include/dynslam/eval/run_records.h)\n"
	   << "dynslam-montecarlo-runs 1\nsweep";
	for (const auto& [k, v] : f.sweep) os << ' ' << k << '=' << v;
	os << '\n';
	for (const auto& r : f.runs)
	{
		const auto& m = r.metrics;
		os << "run " << r.level << ' ' << r.run << ' ' << r.seed << ' ' << r.steps << '\n';
		rmseLine(os, "ego", m.ego);
		rmseLine(os, "static_map", m.static_map);
		os << "scalars " << hx(m.ate) << ' ' << hx(m.ate_aligned) << ' ' << m.ego_skipped << ' '
		   << m.landmarks_missing << ' ' << m.landmarks_unmatched << ' '
		   << m.object_estimates_unmatched << ' ' << hx(m.ms_per_step) << '\n';
		for (const auto& o : m.objects)
		{
			os << "object " << o.object << ' ' << int(o.translation_only) << ' '
			   << o.features_missing << ' ' << o.poses_skipped << '\n';
			rmseLine(os, "features", o.features);
			rmseLine(os, "poses", o.poses);
		}
		const auto& c = r.consistency;
		samplesLine(os, "ego", c.ego);
		samplesLine(os, "landmarks", c.landmarks);
		samplesLine(os, "map", c.map);
		samplesLine(os, "nis", c.nis);
		for (const auto& [id, s] : c.object_poses)
			samplesLine(os, "object:" + std::to_string(id), s);
		os << "map_joint_cov " << int(c.map_joint_cov) << "\nend\n";
	}
}

TRunRecordFile readRunRecords(std::istream& is, const std::string& name)
{
	TReader rd{is, name, 0, {}, {}};
	TRunRecordFile f;
	rd.expect("dynslam-montecarlo-runs");
	if (rd.str() != "1") rd.fail("unsupported version");
	rd.expect("sweep");
	for (std::string kv; rd.cur >> kv;)
	{
		const auto eq = kv.find('=');
		if (eq == std::string::npos) rd.fail("sweep item without '=': " + kv);
		f.sweep[kv.substr(0, eq)] = kv.substr(eq + 1);
	}
	for (std::string w = rd.next(); !w.empty(); w = rd.next())
	{
		if (w != "run") rd.fail("expected 'run', found '" + w + "'");
		TRunRecord r;
		r.level = rd.str();
		r.run = rd.integer<int>();
		r.seed = rd.integer<uint64_t>();
		r.steps = rd.integer<size_t>();
		auto& m = r.metrics;
		m.ego = rd.rmse("ego");
		m.static_map = rd.rmse("static_map");
		rd.expect("scalars");
		m.ate = rd.dbl();
		m.ate_aligned = rd.dbl();
		m.ego_skipped = rd.integer<size_t>();
		m.landmarks_missing = rd.integer<size_t>();
		m.landmarks_unmatched = rd.integer<size_t>();
		m.object_estimates_unmatched = rd.integer<size_t>();
		m.ms_per_step = rd.dbl();
		while (rd.next() == "object")
		{
			TObjectMetrics o;
			o.object = rd.integer<int32_t>();
			o.translation_only = rd.integer<int>() != 0;
			o.features_missing = rd.integer<size_t>();
			o.poses_skipped = rd.integer<size_t>();
			o.features = rd.rmse("features");
			o.poses = rd.rmse("poses");
			m.objects.push_back(o);
		}
		for (; rd.word == "samples"; rd.next())
		{
			std::string nm;
			TNeesSamples s = rd.samples(nm);
			auto& c = r.consistency;
			if (nm == "ego")
				c.ego = s;
			else if (nm == "landmarks")
				c.landmarks = s;
			else if (nm == "map")
				c.map = s;
			else if (nm == "nis")
				c.nis = s;
			else if (nm.rfind("object:", 0) == 0)
				c.object_poses[int32_t(std::stol(nm.substr(7)))] = s;
			else
				rd.fail("unknown samples '" + nm + "'");
		}
		if (rd.word != "map_joint_cov")
			rd.fail("expected 'map_joint_cov', found '" + rd.word + "'");
		r.consistency.map_joint_cov = rd.integer<int>() != 0;
		rd.expect("end");
		f.runs.push_back(std::move(r));
	}
	return f;
}
}  // namespace dynslam::eval
