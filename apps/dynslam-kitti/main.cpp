/** dynslam-kitti: KITTI tracking importer (see dynslam/kitti/CKittiApp.h). */
#include <dynslam/kitti/CKittiApp.h>

#include <exception>
#include <iostream>

int main(int argc, char** argv)
{
	try
	{
		dynslam::kitti::CKittiApp app;
		if (!app.initialize(argc, const_cast<const char**>(argv))) return 0;
		app.run();
		return 0;
	}
	catch (const std::exception& e)
	{
		std::cerr << "dynslam-kitti: error: " << e.what() << "\n";
		return 1;
	}
}
