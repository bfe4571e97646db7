/** dynslam-mrclam: UTIAS MRCLAM importer (see dynslam/mrclam/CMrclamApp.h). */
#include <dynslam/mrclam/CMrclamApp.h>

#include <exception>
#include <iostream>

int main(int argc, char** argv)
{
	try
	{
		dynslam::mrclam::CMrclamApp app;
		if (!app.initialize(argc, const_cast<const char**>(argv))) return app.exitCode();
		app.run();
		return 0;
	}
	catch (const std::exception& e)
	{
		std::cerr << "dynslam-mrclam: error: " << e.what() << "\n";
		return 1;
	}
}
