// Force-included (-include) into Dear ImGui's imgui_impl_opengl3.cpp, which is compiled with
// IMGUI_IMPL_OPENGL_LOADER_CUSTOM: its gl* calls resolve to prep::gl's pointer table (see gl_api.h),
// so the backend works under both GLFW and OSMesa contexts in one binary.
#pragma once
#include "app/render/gl_api.h"
using namespace prep::gl;
