# make install PREFIX=/usr/local [DESTDIR=...]: the header and a pkg-config file.
#   cc $(pkg-config --cflags stereoblend) app.c $(pkg-config --libs stereoblend)
# (the implementation needs libm, hence Libs: -lm). make uninstall removes both.
# CMake users: CMakeLists.txt (add_subdirectory / FetchContent, or find_package after a
# cmake --install).

PREFIX     ?= /usr/local
INCLUDEDIR ?= $(PREFIX)/include
PKGCONFIGDIR ?= $(PREFIX)/share/pkgconfig
SBL_VERSION := $(shell sed -n 's/^\#define SBL_VERSION_MAJOR \([0-9]*\).*/\1/p' stereoblend.h).$(shell sed -n 's/^\#define SBL_VERSION_MINOR \([0-9]*\).*/\1/p' stereoblend.h)

.PHONY: install uninstall
install:
	install -d $(DESTDIR)$(INCLUDEDIR) $(DESTDIR)$(PKGCONFIGDIR)
	install -m 644 stereoblend.h $(DESTDIR)$(INCLUDEDIR)/stereoblend.h
	printf '%s\n' 'prefix=$(PREFIX)' 'includedir=$(INCLUDEDIR)' '' \
	  'Name: stereoblend' \
	  'Description: Variance-guided temporal and stereo reuse for rendered frames (single C99 header)' \
	  'Version: $(SBL_VERSION)' \
	  'Cflags: -I$${includedir}' \
	  'Libs: -lm' > $(DESTDIR)$(PKGCONFIGDIR)/stereoblend.pc
	@echo "installed $(DESTDIR)$(INCLUDEDIR)/stereoblend.h and $(DESTDIR)$(PKGCONFIGDIR)/stereoblend.pc"

uninstall:
	rm -f $(DESTDIR)$(INCLUDEDIR)/stereoblend.h $(DESTDIR)$(PKGCONFIGDIR)/stereoblend.pc
