// Placeholder; the strict loader replaces it.
#include "slam/settings/slam_settings.h"
