# tests/bench: every tests/bench/NAME.cpp is one benchmark program, built and run by `make bench`.
# Benchmarks report ratios against a baseline measured in the same run (this machine is shared).
BENCH_SOURCES := $(wildcard tests/bench/*.cpp)
BENCH_PROGRAMS += $(patsubst tests/bench/%.cpp,$(BUILD)/bench/%,$(BENCH_SOURCES))

$(BUILD)/bench/%: $(BUILD)/obj/tests/bench/%.o $(LIBDSN_TOOLS) $(LIBDSN_BAKE) $(LIBDSN)
	@mkdir -p $(@D)
	$(CXX) $(CXXFLAGS) $< -o $@ $(OFFLINE_LINK)
