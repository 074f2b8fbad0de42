#include "osmesa_context.h"

#include <GL/osmesa.h>

#include <stdexcept>

namespace pbm {

struct OsmesaContext::Impl {
  OSMesaContext context = nullptr;
  std::vector<unsigned char> buffer = std::vector<unsigned char>(4 * 16 * 16);
};

namespace {
void* osmesa_proc(const char* name) {
  return reinterpret_cast<void*>(OSMesaGetProcAddress(name));
}
}  // namespace

OsmesaContext::OsmesaContext() : impl_(std::make_unique<Impl>()) {
  const int attributes[] = {OSMESA_FORMAT,
                            OSMESA_RGBA,
                            OSMESA_DEPTH_BITS,
                            24,
                            OSMESA_PROFILE,
                            OSMESA_CORE_PROFILE,
                            OSMESA_CONTEXT_MAJOR_VERSION,
                            3,
                            OSMESA_CONTEXT_MINOR_VERSION,
                            3,
                            0};
  impl_->context = OSMesaCreateContextAttribs(attributes, nullptr);
  if (impl_->context == nullptr) {
    throw std::runtime_error(
        "OSMesa could not create an OpenGL 3.3 core context (is libosmesa6 built with llvmpipe?)");
  }
  if (!OSMesaMakeCurrent(impl_->context, impl_->buffer.data(), GL_UNSIGNED_BYTE, 16, 16)) {
    OSMesaDestroyContext(impl_->context);
    throw std::runtime_error("OSMesa could not make its context current");
  }
  gl_ = gl::load_functions(&osmesa_proc);
  gl::require_version(gl_, 3, 3);
}

OsmesaContext::~OsmesaContext() {
  if (impl_ && impl_->context != nullptr) OSMesaDestroyContext(impl_->context);
}

}  // namespace pbm
