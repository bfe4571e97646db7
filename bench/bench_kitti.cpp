/** dynslam-bench: the KITTI importer (libs/kitti) on an 800-frame synthetic sequence with the
 * density of KITTI tracking sequence 0009 (803 frames, 5301 label lines: here 800 frames, 5600
 * lines: 2 DontCare, 3 parked and 2 moving cars per frame), written once into a temp folder.
 * BM_KittiImport: read + convert in memory; BM_KittiConvert: the whole dynslam-kitti run
 * (read, convert, write the rawlog and every ground-truth file). doc/kitti.md, section 4. */
#include <benchmark/benchmark.h>
#include <dynslam/kitti/CKittiApp.h>
#include <dynslam/kitti/rawlog_writer.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

namespace
{
const std::string& syntheticSequence()
{
	static const std::string dir = []
	{
		const auto d = std::filesystem::temp_directory_path() / "dynslam_bench_kitti";
		std::filesystem::create_directories(d / "label_02");
		std::filesystem::create_directories(d / "poses");
		std::ofstream p(d / "poses" / "0000.txt"), l(d / "label_02" / "0000.txt");
		p.precision(9);
		l.precision(6);
		for (int k = 0; k < 800; ++k)
		{
			// the camera drives 1 m per frame on a circle of radius 500 m (rotation about y)
			const double a = -double(k) / 500.0, s = std::sin(a), c = std::cos(a);
			const double tx = 500.0 * (1 - std::cos(a)), tz = 500.0 * std::sin(-a);
			p << c << " 0 " << s << ' ' << tx << " 0 1 0 0 " << -s << " 0 " << c << ' ' << tz
			  << "\n";
			for (int j = 0; j < 2; ++j)
				l << k << " -1 DontCare -1 -1 -10 1 2 3 4 -1000 -1000 -1000 -10 -1 -1 -1\n";
			for (int j = 0; j < 3; ++j)  // parked, seen from 30 m down to 5 m ahead
				l << k << ' ' << 3 * (k / 25) + j << " Car 0 0 -1.5 100 150 300 250 1.5 1.8 4 "
				  << (j % 2 ? 4 : -4) << " 1.6 " << 30 - (k % 25) + 5 * j << " -1.5708\n";
			for (int j = 0; j < 2; ++j)  // moving beside the ego
				l << k << ' ' << 1000 + j << " Car 0 0 -1.5 100 150 300 250 1.5 1.8 4 "
				  << (j ? 3.5 : -3.5) << " 1.6 " << 8 + 4 * j + 0.01 * k << " -1.5708\n";
		}
		return d.string();
	}();
	return dir;
}

void BM_KittiImport(benchmark::State& state)
{
	const std::string d = syntheticSequence();
	dynslam::kitti::TImportOptions o;
	size_t readings = 0;
	for (auto _ : state)
	{
		const auto r = dynslam::kitti::importFromFiles(d + "/label_02", d + "/poses", "0000", o);
		readings = r.summary.readings;
		benchmark::DoNotOptimize(r.steps.data());
	}
	state.counters["readings"] = double(readings);
}
BENCHMARK(BM_KittiImport)->Unit(benchmark::kMillisecond);

void BM_KittiConvert(benchmark::State& state)
{
	const std::string d = syntheticSequence();
	dynslam::kitti::TKittiOptions o;
	for (auto _ : state)
	{
		const auto r =
		    dynslam::kitti::importFromFiles(d + "/label_02", d + "/poses", "0000", o.import);
		dynslam::kitti::writeImport(r, o, d + "/out", "kitti_0000");
	}
}
BENCHMARK(BM_KittiConvert)->Unit(benchmark::kMillisecond);
}  // namespace
