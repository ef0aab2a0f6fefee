#include "gui/window.hpp"

#include <GLFW/glfw3.h>

#include <cstdlib>

namespace isolux::app {

namespace {
std::string g_glfw_error;
void on_glfw_error(int, const char* text) { g_glfw_error = text ? text : "unknown GLFW error"; }
}  // namespace

GLFWwindow* open_window(int width, int height, bool visible, std::string& error) {
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
    glfwWindowHint(GLFW_VISIBLE, visible ? GLFW_TRUE : GLFW_FALSE);
    GLFWwindow* w = glfwCreateWindow(width, height, "isolux", nullptr, nullptr);
    if (!w) {
        error = "cannot create an OpenGL 3.3 core window: " + g_glfw_error;
        glfwTerminate();
        return nullptr;
    }
    glfwMakeContextCurrent(w);
    glfwSwapInterval(visible ? 1 : 0);
    return w;
}

void close_window(GLFWwindow* w) {
    if (w) glfwDestroyWindow(w);
    glfwTerminate();
}

}  // namespace isolux::app
