// The one small wrapper over GLFW: a window with a GL 3.3 core context.
#pragma once
#include <string>

struct GLFWwindow;

namespace isolux::app {

// Creates the window and makes its context current. nullptr with `error` set
// when there is no display or no GL 3.3 (GLFW 3.3 has no headless platform).
// With `fit_work_area`, the window (its frame included) is made to fit the
// primary monitor's work area, the screen less its task bars, and opens at
// its top-left: a remembered or default size larger than a small screen
// never leaves panels off-screen. Without it the size is exact (a size the
// user asked for, a hidden window for screenshots).
GLFWwindow* open_window(int width, int height, bool visible, std::string& error, bool fit_work_area = false);
void close_window(GLFWwindow* w);

}  // namespace isolux::app
