# tests/gpu: the GLSL evaluator (include/dsn/dsn.glsl) proven on Mesa's software GPUs. `make gpu-test`
# installs the packages (deps-gpu), validates every shader with glslangValidator and runs the cross test's
# golden program in the shaders (tests/gpu/run-gpu): OpenGL 4.5 and OpenGL ES 3.1 compute, the GLSL ES 3.00
# fragment variant, on llvmpipe and on softpipe; each must print exactly tests/cross/golden.txt.
GPU_PACKAGES := libegl-dev libgles-dev libegl-mesa0 libgl1-mesa-dri glslang-tools
GPU_GOLDEN := $(BUILD)/bin/dsn-gpu-golden
GPU_GENERATED := $(BUILD)/gen
GPU_LIBS := -lEGL

.PHONY: gpu-test deps-gpu
deps-gpu: deps
	@packaging/install-packages $(GPU_PACKAGES)

# Built in a second make, after deps-gpu has installed the headers (all: the smoke test uses dsn-render).
gpu-test: deps-gpu
	@$(MAKE) --no-print-directory all $(GPU_GOLDEN) $(GPU_PROGRAMS)
	@BUILD="$(BUILD)" GPU_SHADER_PROGRAMS="$(GPU_PROGRAMS)" tests/gpu/run-gpu
	@for test in $(GPU_SMOKE_TESTS); do BUILD="$(BUILD)" $$test || exit 1; done

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
