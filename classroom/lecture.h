// classroom/lecture.h: the lecture's renderer (../bdpt.cpp) as every room of the classroom sees it:
// its profile hook filled by profile.h, without the lecture's main. Each room includes this first.
#pragma once
#ifndef BDPT_NO_MAIN
#define BDPT_NO_MAIN
#endif
#include "profile.h"
#include "../bdpt.cpp"
