# examples/demo: the programs behind `make demo` (examples/demo/make-demo): the demo's own exemplar and
# the labelled contact sheet.
$(BUILD)/obj/examples/demo/%.o: examples/demo/%.cpp
	@mkdir -p $(@D)
	$(CXX) $(OFFLINE_FLAGS) $(CXXFLAGS) -c $< -o $@

$(BUILD)/bin/dsn-demo-exemplar: $(BUILD)/obj/examples/demo/demo_exemplar.o $(LIBDSN_TOOLS) $(LIBDSN_BAKE) $(LIBDSN)
	@mkdir -p $(@D)
	$(CXX) $(CXXFLAGS) $< -o $@ $(OFFLINE_LINK)

$(BUILD)/bin/dsn-contact-sheet: $(BUILD)/obj/examples/demo/contact_sheet.o $(LIBDSN_TOOLS) $(LIBDSN_BAKE) $(LIBDSN)
	@mkdir -p $(@D)
	$(CXX) $(CXXFLAGS) $< -o $@ $(OFFLINE_LINK)

PROGRAMS += $(BUILD)/bin/dsn-demo-exemplar $(BUILD)/bin/dsn-contact-sheet
TEST_SCRIPTS += examples/demo/smoke-test
