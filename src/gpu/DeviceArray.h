#pragma once
// A buffer in GPU memory (plain C++ interface; the CUDA calls are in DeviceArray.cu). Grows on
// demand and keeps its allocation for the next frame of the same size. CUDA errors, including
// "out of memory", are thrown as mfadvr::Error with what was being allocated or copied.
#include <cstddef>

namespace mfadvr::gpu {

class DeviceArray {
 public:
  DeviceArray() = default;
  ~DeviceArray();
  DeviceArray(const DeviceArray&) = delete;
  DeviceArray& operator=(const DeviceArray&) = delete;
  DeviceArray(DeviceArray&& other) noexcept;
  DeviceArray& operator=(DeviceArray&& other) noexcept;

  // At least `bytes` bytes (contents undefined); `what` names the buffer in errors.
  void reserve(std::size_t bytes, const char* what);
  // Copies `bytes` bytes from the host (reserving first).
  void upload(const void* host, std::size_t bytes, const char* what);
  // Copies the first `bytes` bytes back to the host.
  void download(void* host, std::size_t bytes) const;
  void zero(std::size_t bytes);
  void release();

  void* data() const { return ptr_; }
  template <class T>
  T* as() const {
    return static_cast<T*>(ptr_);
  }
  std::size_t capacity() const { return capacity_; }

 private:
  void* ptr_ = nullptr;
  std::size_t capacity_ = 0;
};

}  // namespace mfadvr::gpu
