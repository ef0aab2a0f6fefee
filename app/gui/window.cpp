#include "gui/window.hpp"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <cstdlib>

namespace isolux::app {

namespace {
std::string g_glfw_error;
void on_glfw_error(int, const char* text) { g_glfw_error = text ? text : "unknown GLFW error"; }
}  // namespace

GLFWwindow* open_window(int width, int height, bool visible, std::string& error, bool fit_work_area) {
    glfwSetErrorCallback(on_glfw_error);
    if (!glfwInit()) {
        const char* d = std::getenv("DISPLAY");
        error = (d && *d) ? "cannot open the display " + std::string(d) + ": " + g_glfw_error
                          : "no display (DISPLAY is not set)";
        return nullptr;
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    // Hidden until it is sized and placed.
    glfwWindowHint(GLFW_VISIBLE, GLFW_FALSE);
    GLFWwindow* w = glfwCreateWindow(width, height, "isolux", nullptr, nullptr);
    if (!w) {
        error = "cannot create an OpenGL 3.3 core window: " + g_glfw_error;
        glfwTerminate();
        return nullptr;
    }
    GLFWmonitor* monitor = glfwGetPrimaryMonitor();
    if (fit_work_area && monitor) {
        int ax = 0, ay = 0, aw = 0, ah = 0, left = 0, top = 0, right = 0, bottom = 0;
        glfwGetMonitorWorkarea(monitor, &ax, &ay, &aw, &ah);
        glfwGetWindowFrameSize(w, &left, &top, &right, &bottom);
        const int fit_w = std::max(320, std::min(width, aw - left - right)),
                  fit_h = std::max(240, std::min(height, ah - top - bottom));
        if (aw > 0 && ah > 0 && (fit_w != width || fit_h != height)) glfwSetWindowSize(w, fit_w, fit_h);
        if (aw > 0 && ah > 0) glfwSetWindowPos(w, ax + left, ay + top);
    }
    if (visible) glfwShowWindow(w);
    glfwMakeContextCurrent(w);
    glfwSwapInterval(visible ? 1 : 0);
    return w;
}

void close_window(GLFWwindow* w) {
    if (w) glfwDestroyWindow(w);
    glfwTerminate();
}

}  // namespace isolux::app
