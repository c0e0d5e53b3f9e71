#!/bin/sh
# The core never calls the heap itself: no object in libjade_core references
# an allocator, except the decoders (the Draco shim, the glTF reader, the PLY
# strip and OBJ comment rewriters, the texture decoder and its PNG and JPEG
# decoders, the OBJ material reader and the decoded arrays they share and
# split where coarse), which
# the core runs only in the sandboxed child process during loading (the
# program's picture reader uses the PNG decoder too, outside any frame).
lib=$1
bad=$(nm -A "$lib" 2>/dev/null | grep -v -E '(draco_shim|gltf_read|mesh_arrays|mesh_subdivide|ply_strips|obj_check|texture_decode|png_decode|jpeg_decode|obj_material|file_beside)' | grep -E ' U (malloc|calloc|realloc|free|aligned_alloc|posix_memalign|strdup|_Znwm|_Znam|_ZdlPv|_ZdaPv|fopen)$')
objects=$(nm -A "$lib" 2>/dev/null | cut -d: -f2 | sort -u | wc -l)
if [ -n "$bad" ]; then
    echo "core objects reference the heap:"
    echo "$bad"
    echo "core allocation check: 0 passed, 1 failed"
    exit 1
fi
echo "checked $objects core objects: none references malloc/calloc/realloc/free/new/delete/fopen (the decoders of the loader's child excepted)"
echo "core allocation check: 1 passed, 0 failed"
