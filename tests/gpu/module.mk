# tests/gpu: the GLSL evaluator (include/dsn/dsn.glsl) proven on Mesa's software GPUs. `make gpu-test`
# installs the packages (deps-gpu), validates every shader with glslangValidator and runs the cross test's
# golden program in the shaders (tests/gpu/run-gpu): OpenGL 4.5 and OpenGL ES 3.1 compute, the GLSL ES 3.00
# fragment variant, on llvmpipe and on softpipe; each must print exactly tests/cross/golden.txt (the compute
# runs take the lattice tiles and continuous grids through dsn.glsl's workgroup tiles).
# `make gpu-bench` times dsn.glsl against Texton Noise (texton_noise.glsl) on the same OpenGL (gpu_bench.cpp).
GPU_PACKAGES := libegl-dev libgles-dev libegl-mesa0 libgl1-mesa-dri glslang-tools
GPU_GOLDEN := $(BUILD)/bin/dsn-gpu-golden
GPU_BENCH := $(BUILD)/bin/dsn-gpu-bench
GPU_PROGRAMS += $(GPU_BENCH) # (run-gpu validates its shaders)
GPU_GENERATED := $(BUILD)/gen
GPU_LIBS := -lEGL

.PHONY: gpu-test deps-gpu gpu-bench
deps-gpu: deps
	@packaging/install-packages $(GPU_PACKAGES)

# Built in a second make, after deps-gpu has installed the headers (all: the smoke test uses dsn-render).
gpu-test: deps-gpu
	@$(MAKE) --no-print-directory all $(GPU_GOLDEN) $(GPU_PROGRAMS)
	@BUILD="$(BUILD)" GPU_SHADER_PROGRAMS="$(GPU_PROGRAMS)" tests/gpu/run-gpu
	@for test in $(GPU_SMOKE_TESTS); do BUILD="$(BUILD)" $$test || exit 1; done

# On whatever OpenGL EGL's surfaceless platform gives (llvmpipe when there is no GPU).
gpu-bench: deps-gpu
	@$(MAKE) --no-print-directory $(GPU_BENCH)
	EGL_PLATFORM=surfaceless $(GPU_BENCH)

# GLSL sources embedded in the programs as C++ raw string literals (#include "path.glsl.inc").
$(GPU_GENERATED)/%.glsl.inc: %.glsl
	@mkdir -p $(@D)
	{ printf 'R"dsn_glsl('; cat $<; printf ')dsn_glsl"\n'; } >$@

$(BUILD)/obj/tests/gpu/%.o: TEST_FLAGS += -I$(GPU_GENERATED)
$(BUILD)/obj/tests/gpu/gpu_golden.o: $(GPU_GENERATED)/include/dsn/dsn.glsl.inc \
    $(GPU_GENERATED)/tests/gpu/golden_kernel.glsl.inc

$(GPU_GOLDEN): $(BUILD)/obj/tests/gpu/gpu_golden.o $(BUILD)/obj/tests/gpu/headless_gl.o \
    $(BUILD)/obj/tests/cross/golden_assets.o $(LIBDSN)
	@mkdir -p $(@D)
	$(CXX) $(CXXFLAGS) $^ -o $@ $(LDFLAGS) $(GPU_LIBS)

$(BUILD)/obj/tests/gpu/gpu_bench.o: $(GPU_GENERATED)/include/dsn/dsn.glsl.inc \
    $(GPU_GENERATED)/tests/gpu/texton_noise.glsl.inc

# The bench's noise comes from the test fixtures' asset writer: it links the baker's library too.
$(GPU_BENCH): $(BUILD)/obj/tests/gpu/gpu_bench.o $(BUILD)/obj/tests/gpu/headless_gl.o \
    $(LIBDSN_TOOLS) $(LIBDSN_BAKE) $(LIBDSN)
	@mkdir -p $(@D)
	$(CXX) $(CXXFLAGS) $(BUILD)/obj/tests/gpu/gpu_bench.o $(BUILD)/obj/tests/gpu/headless_gl.o -o $@ \
	    $(OFFLINE_LINK) $(GPU_LIBS)
