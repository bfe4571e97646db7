/** dynslam-mrclam: UTIAS MRCLAM importer (see dynslam/mrclam/CMrclamApp.h). */
#include <dynslam/apps/app_main.h>
#include <dynslam/mrclam/CMrclamApp.h>

int main(int argc, char** argv)
{
	return dynslam::apps::runMain("dynslam-mrclam",
	                              [&]
	                              {
		                              dynslam::mrclam::CMrclamApp app;
		                              if (!app.initialize(argc, const_cast<const char**>(argv)))
			                              return 0;
		                              app.run();
		                              return 0;
	                              });
}
