/*
 * libFuzzer target: feeds arbitrary bytes to the scene parser and the mesh loaders through
 * the C ABI. The first byte picks the entry point: 0 → ps_sim_create_from_scene() on the
 * rest as JSON text; 1, 2, 3 → ps_hierarchy_create_from_file() on the rest written to a
 * temporary .obj, .off or .ply file. Every call must return a status, never crash, leak or
 * trip a sanitizer; a successful create must be destroyable.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "progsim.h"

static void fuzz_scene(const uint8_t* data, size_t size) {
  char* text = malloc(size + 1);
  if (!text) return;
  memcpy(text, data, size);
  text[size] = '\0';
  ps_sim* sim = NULL;
  if (ps_sim_create_from_scene(text, "/nonexistent", &sim) == PS_OK) ps_sim_destroy(sim);
  free(text);
}

static void fuzz_mesh(const uint8_t* data, size_t size, const char* extension) {
  char path[64];
  snprintf(path, sizeof path, "/tmp/progsim_fuzz_%d%s", (int)getpid(), extension);
  FILE* file = fopen(path, "wb");
  if (!file) return;
  fwrite(data, 1, size, file);
  fclose(file);
  ps_hierarchy* hierarchy = NULL;
  if (ps_hierarchy_create_from_file(NULL, path, &hierarchy) == PS_OK)
    ps_hierarchy_destroy(hierarchy);
  remove(path);
}

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1 || size > 16384) return 0;
  static const char* const extensions[3] = {".obj", ".off", ".ply"};
  const uint8_t selector = data[0] % 4;
  if (selector == 0)
    fuzz_scene(data + 1, size - 1);
  else
    fuzz_mesh(data + 1, size - 1, extensions[selector - 1]);
  return 0;
}
