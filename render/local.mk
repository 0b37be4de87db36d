# SPDX-License-Identifier: BSD-3-Clause
# render/local.mk - the off-screen renderer sph-render, its test, and the
# `frames` and `golden-render` targets. Included by the top-level Makefile.am.
#
# The renderer links the snapshot reader (src/libsphio.la), never the solver.
# It links OSMesa and EGL but no libGL/libOpenGL: OpenGL entry points are
# loaded through each back end's proc-address function (render/gl_api.c).
# Without pkg-config egl, EGL_LIBS is empty and the egl back end is a stub.

# Everything but main(), so the test can call the layout and colour code.
noinst_LTLIBRARIES += render/libsphrender.la
render_libsphrender_la_SOURCES = \
	render/atomic_file.c render/atomic_file.h \
	render/camera.c render/camera.h \
	render/canvas.c render/canvas.h render/canvas_impl.h \
	render/canvas_cairo.c render/canvas_gl.c \
	render/cli.c render/cli.h render/options.h \
	render/colormap.c render/colormap.h \
	render/contour.c render/contour.h \
	render/figure.c render/figure.h \
	render/font.c render/font.h \
	render/gl_api.c render/gl_api.h \
	render/gl_context.c render/gl_context.h \
	render/gl_context_egl.c \
	render/gl_context_osmesa.c \
	render/gl_program.c render/gl_program.h \
	render/gl_supersample.c render/gl_supersample.h \
	render/inputs.c render/inputs.h \
	render/interp.c render/interp.h \
	render/interp3d.c render/interp3d.h \
	render/isosurface.c render/isosurface.h \
	render/jobs.c render/jobs.h \
	render/label.c render/label.h \
	render/layout.c render/layout.h \
	render/lines_gl.c render/lines_gl.h \
	render/marks.c render/marks.h \
	render/mesh_gl.c render/mesh_gl.h \
	render/mesh_run.c render/mesh_run.h \
	render/obstacles.c render/obstacles.h \
	render/plot.c render/plot.h \
	render/ply_out.c render/ply_out.h render/vtk_out.c render/vtk_out.h \
	render/png_out.c render/png_out.h \
	render/scene3d.c render/scene3d.h \
	render/sequence.c render/sequence.h \
	render/slice.c render/slice.h \
	render/snapdata.c render/snapdata.h \
	render/spheres.c render/spheres.h \
	render/surface.c render/surface.h \
	render/ticks.c render/ticks.h
RENDER_CFLAGS = $(AM_CFLAGS) $(OSMESA_CFLAGS) $(EGL_CFLAGS) $(PNG_CFLAGS) $(HDF5_CFLAGS) \
	$(FREETYPE_CFLAGS) $(CAIRO_CFLAGS)
RENDER_LIBS = src/libsphio.la $(OSMESA_LIBS) $(EGL_LIBS) $(PNG_LIBS) $(HDF5_LIBS) \
	$(FREETYPE_LIBS) $(CAIRO_LIBS) -lm
render_libsphrender_la_CFLAGS = $(RENDER_CFLAGS)

bin_PROGRAMS += render/sph-render
render_sph_render_SOURCES = render/main.c
render_sph_render_CFLAGS = $(RENDER_CFLAGS)
render_sph_render_LDADD = render/libsphrender.la $(RENDER_LIBS)
# spelled out: automake cannot see the libraries inside RENDER_LIBS, and a
# parallel build would otherwise link before src/libsphio.la exists
render_sph_render_DEPENDENCIES = render/libsphrender.la src/libsphio.la

check_PROGRAMS += tests/test_render
TESTS += tests/test_render
tests_test_render_SOURCES = tests/test_render.c tests/render_testutil.c tests/render_testutil.h
tests_test_render_CFLAGS = $(RENDER_CFLAGS) $(CUNIT_CFLAGS) -I$(top_srcdir)/render
tests_test_render_LDADD = tests/libtestutil.la render/libsphrender.la $(RENDER_LIBS) $(CUNIT_LIBS)
tests_test_render_DEPENDENCIES = tests/libtestutil.la render/libsphrender.la src/libsphio.la

check_PROGRAMS += tests/test_render_3d
TESTS += tests/test_render_3d
tests_test_render_3d_SOURCES = tests/test_render_3d.c tests/render_testutil.c tests/render_testutil.h
tests_test_render_3d_CFLAGS = $(RENDER_CFLAGS) $(CUNIT_CFLAGS) -I$(top_srcdir)/render
tests_test_render_3d_LDADD = tests/libtestutil.la render/libsphrender.la $(RENDER_LIBS) $(CUNIT_LIBS)
tests_test_render_3d_DEPENDENCIES = tests/libtestutil.la render/libsphrender.la src/libsphio.la

check_PROGRAMS += tests/test_isosurface
TESTS += tests/test_isosurface
tests_test_isosurface_SOURCES = tests/test_isosurface.c
tests_test_isosurface_CFLAGS = $(RENDER_CFLAGS) $(CUNIT_CFLAGS) -I$(top_srcdir)/render
tests_test_isosurface_LDADD = tests/libtestutil.la render/libsphrender.la $(RENDER_LIBS) $(CUNIT_LIBS)
tests_test_isosurface_DEPENDENCIES = tests/libtestutil.la render/libsphrender.la src/libsphio.la

# `make frames`: the frames of a run (by default the Martin & Moyce run of
# the README's main command) into frames/, one PNG per snapshot.
# Override e.g.: make frames FRAMES_RUN=out/other FRAMES_FLAGS='--field pressure'
FRAMES_RUN = out/martin_moyce
FRAMES_DIR = frames
FRAMES_FLAGS = --field speed --cmap viridis
frames: render/sph-render$(EXEEXT)
	@test -d '$(FRAMES_RUN)' || { echo "no run in $(FRAMES_RUN): first run" \
	  "sph run cases/martin_moyce.yaml -o $(FRAMES_RUN)" >&2; exit 1; }
	render/sph-render$(EXEEXT) $(FRAMES_FLAGS) '$(FRAMES_RUN)' -o '$(FRAMES_DIR)'

# `make movie`: the frames in FRAMES_DIR as MOVIE (an MP4, MOVIE_FPS frames
# per second) with ffmpeg; without ffmpeg it says what to install.
MOVIE = movie.mp4
MOVIE_FPS = 25
movie:
	$(SHELL) '$(srcdir)/render/movie.sh' '$(FRAMES_DIR)' '$(MOVIE)' '$(MOVIE_FPS)'

# Rewrites golden/render/*.png from the current build (a deliberate act:
# commit the new images with the reason they changed).
golden-render: render/sph-render$(EXEEXT) tests/test_render$(EXEEXT) tests/test_render_3d$(EXEEXT)
	SPH_SRCDIR='$(abs_top_srcdir)' SPH_BUILDDIR='$(abs_top_builddir)' SPH_RENDER_REGEN=1 \
	  tests/test_render$(EXEEXT)
	SPH_SRCDIR='$(abs_top_srcdir)' SPH_BUILDDIR='$(abs_top_builddir)' SPH_RENDER_REGEN=1 \
	  tests/test_render_3d$(EXEEXT)

.PHONY: frames golden-render movie
