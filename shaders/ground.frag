#version 330 core
// The floor where shadows can fall (ground.glsl).
#define FLOOR_SHADOWS 1
#include "ground.glsl"
