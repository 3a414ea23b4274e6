#include "continuum/parameters.hpp"
