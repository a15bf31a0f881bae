// Dear ImGui on either context: with a GLFW window (imgui_impl_glfw for input) or headless (display size
// and time set by hand, no input), drawn by imgui_impl_opengl3 through prep's GL pointer table. The
// panels are drawn into the same framebuffer as the scene, so headless screenshots show them.
#pragma once

struct GLFWwindow;
struct ImGuiContext;

namespace prep::render {

class ImGuiLayer {
 public:
  // window == nullptr: headless.
  explicit ImGuiLayer(GLFWwindow* window);
  ~ImGuiLayer();
  ImGuiLayer(const ImGuiLayer&) = delete;
  ImGuiLayer& operator=(const ImGuiLayer&) = delete;

  // Starts a frame of width x height pixels that lasted dt seconds (headless: the caller's clock).
  void begin_frame(int width, int height, float dt);
  // Renders the frame's panels into the current framebuffer.
  void end_frame();
  // Ends the frame's logic (input, layout) without drawing it: the caller shows the panels' last pixels.
  void end_frame_without_drawing();

 private:
  GLFWwindow* window_;
  ImGuiContext* context_ = nullptr;
};

}  // namespace prep::render
