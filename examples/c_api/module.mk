# examples/c_api: a C99 program with an asset compiled in. The asset is written by dsn-example-asset at
# build time and turned into a C array by od and awk (no xxd needed); the program is compiled as strict
# C99 and linked with the C compiler, which also proves that libdsn.a needs no C++ runtime.
C_API_GENERATED := $(BUILD)/gen/c_api
C_API_PROGRAM := $(BUILD)/bin/dsn-c-api-example

$(C_API_GENERATED)/example_asset.dsnt: $(BUILD)/bin/dsn-example-asset
	@mkdir -p $(@D)
	$(BUILD)/bin/dsn-example-asset $@ --channels 3 --radius 5

$(C_API_GENERATED)/example_asset.h: $(C_API_GENERATED)/example_asset.dsnt
	od -An -v -tu1 $< | awk 'BEGIN { print "/* generated from example_asset.dsnt by examples/c_api/module.mk */"; \
	    print "static const unsigned char example_asset[] = {" } \
	    { line = "   "; for (i = 1; i <= NF; i++) { line = line " " $$i ","; n++ } print line } \
	    END { print "};"; print "static const size_t example_asset_size = " n ";" }' > $@.tmp && mv $@.tmp $@

$(BUILD)/obj/examples/c_api/main.o: examples/c_api/main.c $(C_API_GENERATED)/example_asset.h
	@mkdir -p $(@D)
	$(CC) -std=c99 -Wall -Wextra -Werror -pedantic $(CFLAGS) -Iinclude -I$(C_API_GENERATED) -c $< -o $@

$(C_API_PROGRAM): $(BUILD)/obj/examples/c_api/main.o $(LIBDSN)
	@mkdir -p $(@D)
	$(CC) $(CFLAGS) $< -o $@ $(LIBDSN) $(LDFLAGS)

PROGRAMS += $(C_API_PROGRAM)
TEST_SCRIPTS += examples/c_api/smoke-test
