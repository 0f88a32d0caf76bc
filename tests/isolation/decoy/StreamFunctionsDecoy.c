/* A library with the bit-stream function names that libzfp exports, under CFITSIO's signatures
 * (CFITSIO, which ParaView's readers load into every ParaView process, defines these five). The
 * ZFP isolation test links it ahead of everything, so that the dynamic linker binds any lookup
 * of these names in the global scope here. Each call is counted, never acted on. */
#include <stdio.h>

static int calls = 0;

int decoy_stream_calls(void) {
  return calls;
}

int stream_open(char* filename, int rwmode, int* handle) {
  (void)filename;
  (void)rwmode;
  (void)handle;
  return ++calls;
}
int stream_close(int handle) {
  (void)handle;
  return ++calls;
}
int stream_flush(int handle) {
  (void)handle;
  return ++calls;
}
int stream_size(int handle, long long* filesize) {
  (void)handle;
  (void)filesize;
  return ++calls;
}
int stream_read(int handle, void* buffer, long nbytes) {
  (void)handle;
  (void)buffer;
  (void)nbytes;
  return ++calls;
}
