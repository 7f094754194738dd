# tests/fresh-machine: `make fresh-check` runs the README's two commands on a really fresh Debian (a
# debootstrap minbase root, as root through chroot; tests/fresh-machine/fresh-check says how, and how long).
#   make fresh-check FRESH_CHECK_OPTIONS=--no-cache    also: --no-shared, --keep
.PHONY: fresh-check
fresh-check:
	@tests/fresh-machine/fresh-check $(FRESH_CHECK_OPTIONS)
