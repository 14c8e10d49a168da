// Placeholder so that the target builds while the tracker is written; replaced by the real system.
#include "slam/core/slam_system.h"
