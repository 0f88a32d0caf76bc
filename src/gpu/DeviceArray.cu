#include <cuda_runtime.h>

#include <utility>

#include "gpu/CudaCheck.h"
#include "gpu/DeviceArray.h"

namespace mfadvr::gpu {

DeviceArray::~DeviceArray() {
  release();
}

DeviceArray::DeviceArray(DeviceArray&& other) noexcept
    : ptr_(std::exchange(other.ptr_, nullptr)), capacity_(std::exchange(other.capacity_, 0)) {}

DeviceArray& DeviceArray::operator=(DeviceArray&& other) noexcept {
  if (this != &other) {
    release();
    ptr_ = std::exchange(other.ptr_, nullptr);
    capacity_ = std::exchange(other.capacity_, 0);
  }
  return *this;
}

void DeviceArray::release() {
  if (ptr_) cudaFree(ptr_);  // no throw from a destructor; a failed free leaks at worst
  ptr_ = nullptr;
  capacity_ = 0;
}

void DeviceArray::reserve(std::size_t bytes, const char* what) {
  if (bytes <= capacity_ && ptr_) return;
  release();
  const std::size_t size = bytes > 0 ? bytes : 1;
  const cudaError_t status = cudaMalloc(&ptr_, size);
  if (status != cudaSuccess) {
    ptr_ = nullptr;
    std::size_t freeBytes = 0, totalBytes = 0;
    cudaGetLastError();  // clear the sticky allocation error before asking
    cudaMemGetInfo(&freeBytes, &totalBytes);
    throw Error(std::string("CUDA: cannot allocate ") + std::to_string(size >> 20) + " MiB for " +
                what + " (" + std::to_string(freeBytes >> 20) + " of " +
                std::to_string(totalBytes >> 20) +
                " MiB free on the GPU): " + cudaGetErrorString(status));
  }
  capacity_ = size;
}

void DeviceArray::upload(const void* host, std::size_t bytes, const char* what) {
  reserve(bytes, what);
  if (bytes > 0)
    cudaCheck(cudaMemcpy(ptr_, host, bytes, cudaMemcpyHostToDevice),
              std::string("copying ") + what + " to the GPU");
}

void DeviceArray::download(void* host, std::size_t bytes) const {
  if (bytes > 0)
    cudaCheck(cudaMemcpy(host, ptr_, bytes, cudaMemcpyDeviceToHost), "copying from the GPU");
}

void DeviceArray::zero(std::size_t bytes) {
  if (bytes > 0) cudaCheck(cudaMemset(ptr_, 0, bytes), "clearing GPU memory");
}

}  // namespace mfadvr::gpu
