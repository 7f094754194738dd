# tests/fuzz: libFuzzer targets (clang, ASan + UBSan). `make fuzz FUZZ_SECONDS=N` builds each
# tests/fuzz/fuzz_NAME.cpp and runs it for N seconds from its committed seed corpus
# tests/fuzz/corpus/NAME/ (new inputs go to a scratch copy in $(BUILD)/fuzz, never into the tree).
# The asset CRC check is compiled out (FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION) so inputs reach the
# field checks. An input that runs longer than FUZZ_TIMEOUT seconds (a hang) or takes more than
# FUZZ_RSS_LIMIT_MB of memory is a finding, like a crash.
# Targets: image_input (every accepted format, and refused ones, in its seeds), asset_loader,
# asset_roundtrip, command_line (the tools' shared argument parsing).
FUZZ_SECONDS ?= 60
FUZZ_TIMEOUT ?= 10
FUZZ_RSS_LIMIT_MB ?= 2048
FUZZ_CXX ?= clang++
FUZZ_SANITIZERS := -fsanitize=address,undefined -fno-sanitize-recover=all \
    -fsanitize-ignorelist=tests/fuzz/stb_ignorelist.txt
FUZZ_FLAGS = -std=c++17 -O1 -g $(FUZZ_SANITIZERS) -DFUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION \
    -ffp-contract=off -Iinclude -Iruntime -I. $(PACKAGE_CFLAGS)
FUZZ_NAMES := $(patsubst tests/fuzz/fuzz_%.cpp,%,$(wildcard tests/fuzz/fuzz_*.cpp))
FUZZ_PROGRAMS := $(FUZZ_NAMES:%=$(BUILD)/fuzz/fuzz_%)
FUZZ_LIBRARY_SOURCES := $(RUNTIME_SOURCES) $(OFFLINE_SOURCES) $(TOOLS_LIBRARY_SOURCES)
FUZZ_LIBRARY_OBJECTS := $(FUZZ_LIBRARY_SOURCES:%.cpp=$(BUILD)/fuzz/obj/%.o)

$(BUILD)/fuzz/obj/%.o: %.cpp
	@mkdir -p $(@D)
	$(FUZZ_CXX) $(FUZZ_FLAGS) $(RUNTIME_DISPATCH_FLAGS) -fsanitize=fuzzer-no-link $(RUNTIME_FILE_FLAGS) -c $< -o $@
$(BUILD)/fuzz/obj/runtime/kernels/kernel_avx2.o: RUNTIME_FILE_FLAGS = $(KERNEL_AVX2_FLAGS)
$(BUILD)/fuzz/obj/runtime/kernels/kernel_avx512.o: RUNTIME_FILE_FLAGS = $(KERNEL_AVX512_FLAGS)

$(BUILD)/fuzz/fuzz_%: tests/fuzz/fuzz_%.cpp $(FUZZ_LIBRARY_OBJECTS)
	@mkdir -p $(@D)
	$(FUZZ_CXX) $(FUZZ_FLAGS) -fsanitize=fuzzer $^ -o $@ $(PACKAGE_LIBS) -lpthread

.PHONY: fuzz fuzz-build
fuzz-build: deps
	@$(MAKE) --no-print-directory $(FUZZ_PROGRAMS)

fuzz: fuzz-build
	@for name in $(FUZZ_NAMES); do \
	    scratch=$(BUILD)/fuzz/corpus-$$name; mkdir -p $$scratch tests/fuzz/corpus/$$name; \
	    echo "== fuzz_$$name for $(FUZZ_SECONDS) s"; \
	    $(BUILD)/fuzz/fuzz_$$name -max_total_time=$(FUZZ_SECONDS) -timeout=$(FUZZ_TIMEOUT) \
	        -rss_limit_mb=$(FUZZ_RSS_LIMIT_MB) -print_final_stats=1 \
	        -artifact_prefix=$(BUILD)/fuzz/ $$scratch tests/fuzz/corpus/$$name > $(BUILD)/fuzz/$$name.log 2>&1 \
	        || { tail -n 40 $(BUILD)/fuzz/$$name.log; echo "fuzz_$$name: FAILED (artifact in $(BUILD)/fuzz/)"; exit 1; }; \
	    grep -E 'stat::number_of_executed_units|stat::peak_rss_mb|^Done|cov: ' $(BUILD)/fuzz/$$name.log | tail -n 4 | sed "s/^/fuzz_$$name: /"; \
	done
