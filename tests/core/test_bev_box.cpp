/** models::bevIoU (bev_box.h) against closed forms of the intersection of oriented boxes. */
#include <dynslam/core/models/bev_box.h>
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

using dynslam::models::bevCentreDistance;
using dynslam::models::bevCorners;
using dynslam::models::bevIoU;
using dynslam::models::TBevBox;

TEST(BevBox, CornersCounterClockwise)
{
	// 4 x 2 box at (1, 2) heading +90 deg: the length along +y
	const auto k = bevCorners({1, 2, M_PI / 2, 4, 2});
	EXPECT_NEAR(k(0, 0), 0, 1e-12);  // (+l/2, +w/2) -> (1 - 1, 2 + 2)
	EXPECT_NEAR(k(1, 0), 4, 1e-12);
	EXPECT_NEAR(k(0, 2), 2, 1e-12);  // (-l/2, -w/2) -> (1 + 1, 2 - 2)
	EXPECT_NEAR(k(1, 2), 0, 1e-12);
}

TEST(BevBox, IoUClosedForms)
{
	// identical; heading + pi and - pi describe the same footprint
	EXPECT_NEAR(bevIoU({0, 0, 0.3, 4, 2}, {0, 0, 0.3, 4, 2}), 1, 1e-12);
	EXPECT_NEAR(bevIoU({0, 0, 0.3, 4, 2}, {0, 0, 0.3 + M_PI, 4, 2}), 1, 1e-12);
	EXPECT_NEAR(bevIoU({0, 0, M_PI, 4, 2}, {0, 0, -M_PI, 4, 2}), 1, 1e-12);
	// axis-aligned 4 x 2 boxes shifted by d along the length: (4 - d) 2 / (16 - (4 - d) 2)
	// = (4 - d) / (4 + d); d = 1: 3/5
	EXPECT_NEAR(bevIoU({0, 0, 0, 4, 2}, {1, 0, 0, 4, 2}), 0.6, 1e-12);
	// crossed (perpendicular, same centre): intersection w x w = 4, union 8 + 8 - 4 = 12
	EXPECT_NEAR(bevIoU({0, 0, 0, 4, 2}, {0, 0, M_PI / 2, 4, 2}), 1.0 / 3.0, 1e-12);
	// concentric squares of side a at 45 deg: the regular octagon, area 2 (sqrt2 - 1) a^2;
	// IoU = (2 sqrt2 - 2) / (2 - (2 sqrt2 - 2)) = 1 / sqrt2 for any a
	EXPECT_NEAR(bevIoU({0, 0, 0, 3, 3}, {0, 0, M_PI / 4, 3, 3}), 1 / std::sqrt(2.0), 1e-12);
	// square [-1, 1]^2 and the same square turned 45 deg about (1, 0): the diamond's half
	// x <= 1 (area 2) minus the two corners beyond |y| = 1 (legs sqrt2 - 1 each):
	// 2 - (sqrt2 - 1)^2 = 2 sqrt2 - 1; IoU = (2 sqrt2 - 1) / (8 - (2 sqrt2 - 1))
	const double inter = 2 * std::sqrt(2.0) - 1;
	EXPECT_NEAR(bevIoU({0, 0, 0, 2, 2}, {1, 0, M_PI / 4, 2, 2}), inter / (8 - inter), 1e-12);
	EXPECT_NEAR(bevIoU({1, 0, M_PI / 4, 2, 2}, {0, 0, 0, 2, 2}), inter / (8 - inter), 1e-12);
	// apart; touching along an edge
	EXPECT_EQ(bevIoU({0, 0, 0, 4, 2}, {10, 0, 0.5, 4, 2}), 0);
	EXPECT_NEAR(bevIoU({0, 0, 0, 4, 2}, {4, 0, 0, 4, 2}), 0, 1e-12);
	// one inside the other: area ratio
	EXPECT_NEAR(bevIoU({0, 0, 0, 4, 2}, {0.5, 0.2, 0.1, 1, 0.5}), 0.5 / 8, 1e-12);
}

TEST(BevBox, BadBoxesAndDistance)
{
	EXPECT_THROW(bevIoU({0, 0, 0, 0, 2}, {0, 0, 0, 4, 2}), std::invalid_argument);
	EXPECT_THROW(bevIoU({0, 0, 0, 4, 2}, {0, 0, 0, 4, NAN}), std::invalid_argument);
	EXPECT_THROW(bevIoU({NAN, 0, 0, 4, 2}, {0, 0, 0, 4, 2}), std::invalid_argument);
	EXPECT_NEAR(bevCentreDistance({1, 1, 0, 4, 2}, {4, 5, 2, 1, 1}), 5, 1e-12);
}
