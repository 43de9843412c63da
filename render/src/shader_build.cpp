// Compiling and linking a GLSL program, with the compiler's log as the error.
#include "shader_build.h"

namespace render {
namespace {

bool CompileShader(const GlFunctions& fn, GLenum type, const char* source,
                   const std::string& name, GLuint& shader, std::string& error) {
  shader = fn.CreateShader(type);
  fn.ShaderSource(shader, 1, &source, nullptr);
  fn.CompileShader(shader);
  GLint ok = GL_FALSE;
  fn.GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok == GL_TRUE) return true;
  char log[1024] = {};
  fn.GetShaderInfoLog(shader, sizeof log, nullptr, log);
  error = "the " + (name.empty() ? std::string() : name + " ") +
          (type == GL_VERTEX_SHADER ? "vertex" : "fragment") + " shader does not compile: " + log;
  fn.DeleteShader(shader);
  return false;
}

}  // namespace

bool BuildProgram(const GlFunctions& fn, const char* vertex_source, const char* fragment_source,
                  const std::string& name, GLuint& program, std::string& error) {
  GLuint vertex = 0;
  GLuint fragment = 0;
  if (!CompileShader(fn, GL_VERTEX_SHADER, vertex_source, name, vertex, error)) return false;
  if (!CompileShader(fn, GL_FRAGMENT_SHADER, fragment_source, name, fragment, error)) {
    fn.DeleteShader(vertex);
    return false;
  }
  program = fn.CreateProgram();
  fn.AttachShader(program, vertex);
  fn.AttachShader(program, fragment);
  fn.LinkProgram(program);
  // The program keeps the compiled code; the shader objects can go once it is linked.
  fn.DeleteShader(vertex);
  fn.DeleteShader(fragment);
  GLint ok = GL_FALSE;
  fn.GetProgramiv(program, GL_LINK_STATUS, &ok);
  if (ok == GL_TRUE) return true;
  char log[1024] = {};
  fn.GetProgramInfoLog(program, sizeof log, nullptr, log);
  error = "the " + (name.empty() ? std::string() : name + " ") +
          "shader program does not link: " + log;
  return false;
}

GLuint NewQuadArray(const GlFunctions& fn, GLuint quad_buffer) {
  GLuint vertex_array = 0;
  fn.GenVertexArrays(1, &vertex_array);
  fn.BindVertexArray(vertex_array);
  fn.BindBuffer(GL_ARRAY_BUFFER, quad_buffer);
  fn.EnableVertexAttribArray(0);
  fn.VertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 2 * sizeof(float), nullptr);
  return vertex_array;
}

void NewInstancedQuad(const GlFunctions& fn, GLuint quad_buffer, GLuint& vertex_array, GLuint& instance_buffer) {
  vertex_array = NewQuadArray(fn, quad_buffer);
  fn.GenBuffers(1, &instance_buffer);
  fn.BindBuffer(GL_ARRAY_BUFFER, instance_buffer);
}

}  // namespace render
