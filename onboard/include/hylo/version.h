/*
 * hylo's version (semantic versioning), the one source of truth: the
 * library (hylo_version()), the trainer (--version and the models'
 * provenance), hylo.pc and the CMake package (make install reads the three
 * numbers below) all take it from here.
 */
#ifndef HYLO_VERSION_H
#define HYLO_VERSION_H

#define HYLO_VERSION_MAJOR 0
#define HYLO_VERSION_MINOR 1
#define HYLO_VERSION_PATCH 0

#define HYLO_VERSION_STR_(x) #x
#define HYLO_VERSION_STR(x) HYLO_VERSION_STR_(x)
/* "MAJOR.MINOR.PATCH", a string literal. */
#define HYLO_VERSION                                                                  \
	HYLO_VERSION_STR(HYLO_VERSION_MAJOR) "." HYLO_VERSION_STR(HYLO_VERSION_MINOR) "." \
	HYLO_VERSION_STR(HYLO_VERSION_PATCH)
/* One number that orders versions: MAJOR * 10000 + MINOR * 100 + PATCH. */
#define HYLO_VERSION_NUMBER (HYLO_VERSION_MAJOR * 10000 + HYLO_VERSION_MINOR * 100 + HYLO_VERSION_PATCH)

#ifdef __cplusplus
extern "C" {
#endif

/**
 * The version the library was built as: HYLO_VERSION of its own build, to
 * compare with the headers' HYLO_VERSION when the two may come from
 * different installs. Never NULL; no allocation.
 */
const char *hylo_version(void);

#ifdef __cplusplus
}
#endif

#endif
