/** Writes the seed corpora of the fuzz targets: write_seeds <rawlog_dir> <ini_dir>. */
#include <fstream>
#include <iostream>

#include "fuzz_entries.h"

int main(int argc, char** argv)
{
	if (argc != 3)
	{
		std::cerr << "usage: dynslam-fuzz-seeds <rawlog_corpus_dir> <ini_corpus_dir>\n";
		return 1;
	}
	int i = 0;
	for (const auto& s : dynslam_fuzz::rawlogSeeds())
		std::ofstream(std::string(argv[1]) + "/seed" + std::to_string(i++), std::ios::binary)
		    .write(reinterpret_cast<const char*>(s.data()), std::streamsize(s.size()));
	i = 0;
	for (const auto& s : dynslam_fuzz::iniSeeds())
		std::ofstream(std::string(argv[2]) + "/seed" + std::to_string(i++) + ".ini") << s;
	return 0;
}
