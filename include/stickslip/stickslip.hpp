// Umbrella header of the stickslip core library.
#pragma once
#include "stickslip/accumulators/histogram.hpp"
#include "stickslip/accumulators/mean_variance.hpp"
#include "stickslip/belt_switches.hpp"
#include "stickslip/episode.hpp"
#include "stickslip/error.hpp"
#include "stickslip/initial_conditions.hpp"
#include "stickslip/integrator.hpp"
#include "stickslip/observer.hpp"
#include "stickslip/parameters.hpp"
#include "stickslip/random_stream.hpp"
#include "stickslip/statistics.hpp"
#include "stickslip/sweep.hpp"
