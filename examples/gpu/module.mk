# examples/gpu: dsn-gpu-render, the demo's synthesis rendered by include/dsn/dsn.glsl in a GLSL ES 3.00
# fragment shader (headless, EGL surfaceless), writing the PNG that dsn-render writes (a mix too: it reads
# the --mix weight image with libdsn_bake's image reader). Built and checked by
# `make gpu-test` (tests/gpu/module.mk: it needs the EGL and GLES packages), not by `make all`.
GPU_RENDER := $(BUILD)/bin/dsn-gpu-render
GPU_PROGRAMS += $(GPU_RENDER)
GPU_SMOKE_TESTS += examples/gpu/smoke-test

$(BUILD)/obj/examples/gpu/%.o: examples/gpu/%.cpp
	@mkdir -p $(@D)
	$(CXX) $(OFFLINE_FLAGS) -Itests/gpu -I$(BUILD)/gen $(CXXFLAGS) -c $< -o $@
$(BUILD)/obj/examples/gpu/dsn_gpu_render.o: $(BUILD)/gen/include/dsn/dsn.glsl.inc

$(GPU_RENDER): $(BUILD)/obj/examples/gpu/dsn_gpu_render.o $(BUILD)/obj/tests/gpu/headless_gl.o \
    $(LIBDSN_TOOLS) $(LIBDSN_BAKE) $(LIBDSN)
	@mkdir -p $(@D)
	$(CXX) $(CXXFLAGS) $^ -o $@ $(LDFLAGS) $(STB_LIBS) -lEGL
