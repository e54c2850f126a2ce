# make cross-test: the planning core and its unit tests built for aarch64
# (the Jetson / Raspberry Pi class) with Debian's cross compiler and run
# under qemu-aarch64, and a reference plan digest compared bit for bit with
# the x86-64 build. Installs the cross packages (and arm64 cmocka/libsvm
# through multiarch) when missing.
CROSS_CC ?= aarch64-linux-gnu-gcc
# The native CFLAGS are not the target's: CROSS_CFLAGS replaces them.
CROSS_CFLAGS ?= -O2 -g
CROSS_C99_FLAGS := $(C99_REQUIRED) $(CROSS_CFLAGS)
CROSS_DIR := $(BUILD)/aarch64
CROSS_LIBDIR := /usr/lib/aarch64-linux-gnu
CROSS_RUN := qemu-aarch64 -L /usr/aarch64-linux-gnu -E LD_LIBRARY_PATH=$(CROSS_LIBDIR)
CROSS_TEST_NAMES := $(ONBOARD_TEST_NAMES)
CROSS_TESTS := $(CROSS_TEST_NAMES:%=$(CROSS_DIR)/test/%)
CROSS_DIGEST := $(CROSS_DIR)/plan_digest
NATIVE_DIGEST := $(BUILD)/cross/plan_digest

cross-deps:
	@tools/install-deps gcc-aarch64-linux-gnu libc6-dev-arm64-cross qemu-user
	@dpkg --print-foreign-architectures | grep -q arm64 || { \
		echo "cross-test: enabling the arm64 architecture for libcmocka-dev:arm64 and libsvm-dev:arm64"; \
		$$( [ "$$(id -u)" -eq 0 ] || echo sudo ) dpkg --add-architecture arm64; \
		$$( [ "$$(id -u)" -eq 0 ] || echo sudo ) apt-get update -qq; }
	@tools/install-deps libcmocka-dev:arm64 libsvm-dev:arm64

$(CROSS_DIR)/lib/libhylo.a: $(ONBOARD_SRCS) $(ONBOARD_HEADERS) | cross-deps
	@mkdir -p $(CROSS_DIR)/obj $(@D)
	cd $(CROSS_DIR)/obj && $(CROSS_CC) $(CROSS_C99_FLAGS) $(addprefix -I$(CURDIR)/,onboard/include onboard) \
		-c $(addprefix $(CURDIR)/,$(ONBOARD_SRCS))
	rm -f $@ && aarch64-linux-gnu-ar rcs $@ $(CROSS_DIR)/obj/*.o

# The message code: lcm-gen's output with its own flags (mk/msgs.mk), the
# adaptors with the core's.
$(CROSS_DIR)/lib/libhylo_msg.a: $(MSG_NOPUBSUB_SRCS) onboard/msg/convert.c onboard/msg/wire.c $(LCM_STAMP) | cross-deps
	@mkdir -p $(CROSS_DIR)/msgobj $(@D)
	cd $(CROSS_DIR)/msgobj && $(CROSS_CC) $(LCM_GEN_REQUIRED) $(CROSS_CFLAGS) -c $(addprefix $(CURDIR)/,$(MSG_NOPUBSUB_SRCS)) && \
		$(CROSS_CC) $(CROSS_C99_FLAGS) $(addprefix -I$(CURDIR)/,onboard/include onboard onboard/msg $(LCM_GEN_DIR)/c-nopubsub) \
		-c $(CURDIR)/onboard/msg/convert.c $(CURDIR)/onboard/msg/wire.c
	rm -f $@ && aarch64-linux-gnu-ar rcs $@ $(CROSS_DIR)/msgobj/*.o

$(CROSS_DIR)/test/%: tests/onboard/%.c $(CROSS_DIR)/lib/libhylo.a $(CROSS_DIR)/lib/libhylo_msg.a
	@mkdir -p $(@D)
	$(CROSS_CC) $(CROSS_C99_FLAGS) $(TEST_INC) -isystem /usr/include $< $(CROSS_DIR)/lib/libhylo_msg.a \
		$(CROSS_DIR)/lib/libhylo.a -L$(CROSS_LIBDIR) -Wl,-rpath-link,$(CROSS_LIBDIR) \
		$(TEST_LDFLAGS_$*) -lsvm -lcmocka -lm -o $@

$(CROSS_DIGEST): tools/cross/plan_digest.c $(CROSS_DIR)/lib/libhylo.a $(MODEL_HEADERS)
	$(CROSS_CC) $(CROSS_C99_FLAGS) -static $(ONBOARD_INC) -Itests -Ionboard/models $< $(CROSS_DIR)/lib/libhylo.a -lm -o $@

$(NATIVE_DIGEST): tools/cross/plan_digest.c $(ONBOARD_LIB) $(MODEL_HEADERS) $(wildcard tests/onboard/testutil_*.h)
	@mkdir -p $(@D)
	$(CC) $(C99_FLAGS) $(LDFLAGS) $(ONBOARD_INC) -Itests -Ionboard/models $< $(ONBOARD_LIB) -lm -o $@

# The same without the SVR evaluator's AVX2 clones (tests/cross/test_paths.sh).
NATIVE_DIGEST_SSE2 := $(BUILD)/cross/plan_digest_sse2
$(NATIVE_DIGEST_SSE2): tools/cross/plan_digest.c $(ONBOARD_SRCS) $(MODEL_HEADERS) $(ONBOARD_HEADERS) $(wildcard tests/onboard/testutil_*.h)
	@mkdir -p $(@D)
	$(CC) $(C99_FLAGS) $(LDFLAGS) -DHYLO_NO_CLONES $(ONBOARD_INC) -Itests -Ionboard/models $< $(ONBOARD_SRCS) -lm -o $@

ALL_TARGETS += $(NATIVE_DIGEST) $(NATIVE_DIGEST_SSE2)
tests/cross/test_paths.sh: $(NATIVE_DIGEST) $(NATIVE_DIGEST_SSE2)
TESTS += tests/cross/test_paths.sh

cross-test: cross-deps $(CROSS_TESTS) $(CROSS_DIGEST) $(NATIVE_DIGEST)
	@CROSS_RUN="$(CROSS_RUN)" tools/cross/run $(CROSS_DIGEST) $(NATIVE_DIGEST) $(CROSS_TESTS)
