#version 330 core
// The floor where no shadow can fall (ground.glsl).
#define FLOOR_SHADOWS 0
#include "ground.glsl"
