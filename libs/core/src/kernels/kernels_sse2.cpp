/** The kernels with the build's baseline flags (the portable variant). Plain Eigen: its
 * template instantiations are the same as those of every other translation unit. */
#define DYNSLAM_KERNEL_NS sse2
#include "kernels_body.h"
