package painleve.importers;

import java.io.File;
import java.io.PrintStream;
import java.util.Locale;
import java.util.zip.ZipFile;

import javax.xml.parsers.DocumentBuilderFactory;

import no.ntnu.ihb.fmi4j.importer.fmi2.CoSimulationSlave;
import no.ntnu.ihb.fmi4j.importer.fmi2.Fmu;
import org.javafmi.proxy.Status;
import org.javafmi.wrapper.Simulation;
import org.w3c.dom.Document;
import org.w3c.dom.Element;
import org.w3c.dom.NodeList;

/**
 * Runs PainleveRod.fmu through FMI 2.0 Co-Simulation with one of two JVM importers,
 * FMI4j or JavaFMI, and prints the outputs after every communication step as CSV.
 *
 * Usage: CoSimulate fmi4j|javafmi FMU STOP_TIME STEPS
 *
 * Both masters call fmi2DoStep with the same fixed step STOP_TIME/STEPS; the FMU's own
 * CVODE integrates inside each step. Nothing else is set: the default experiment.
 * Exit status 1 when the importer or the FMU reports an error (the message on stderr).
 */
public final class CoSimulate {

    /** The rod's outputs, in the CSV's column order (names from modelDescription.xml). */
    static final String[] REALS = {"x", "v", "y", "w", "theta", "phi", "F_N", "F_T", "energy"};
    static long[] REAL_VRS, MODE_VR, CONTACT_VR;

    /** The value references of `names`, read from the FMU's modelDescription.xml. */
    static long[] valueReferences(File fmu, String... names) throws Exception {
        try (ZipFile zip = new ZipFile(fmu)) {
            Document md = DocumentBuilderFactory.newInstance().newDocumentBuilder()
                    .parse(zip.getInputStream(zip.getEntry("modelDescription.xml")));
            NodeList variables = md.getElementsByTagName("ScalarVariable");
            long[] vrs = new long[names.length];
            for (int k = 0; k < names.length; ++k) {
                vrs[k] = -1;
                for (int i = 0; i < variables.getLength(); ++i) {
                    Element v = (Element) variables.item(i);
                    if (v.getAttribute("name").equals(names[k])) {
                        vrs[k] = Long.parseLong(v.getAttribute("valueReference"));
                    }
                }
                if (vrs[k] < 0) {
                    fail("no variable " + names[k] + " in " + fmu);
                }
            }
            return vrs;
        }
    }

    static void readValueReferences(File fmu) throws Exception {
        REAL_VRS = valueReferences(fmu, REALS);
        MODE_VR = valueReferences(fmu, "mode");
        CONTACT_VR = valueReferences(fmu, "contact");
    }

    private CoSimulate() {
    }

    public static void main(String[] args) throws Exception {
        if (args.length != 4) {
            System.err.println("usage: CoSimulate fmi4j|javafmi FMU STOP_TIME STEPS");
            System.exit(2);
        }
        String importer = args[0];
        File fmu = new File(args[1]);
        double stop = Double.parseDouble(args[2]);
        int steps = Integer.parseInt(args[3]);
        readValueReferences(fmu);
        PrintStream out = System.out;
        out.println("time," + String.join(",", REALS) + ",mode,contact");
        switch (importer) {
            case "fmi4j" -> runFmi4j(fmu, stop, steps, out);
            case "javafmi" -> runJavaFmi(fmu, stop, steps, out);
            default -> {
                System.err.println("unknown importer " + importer);
                System.exit(2);
            }
        }
        out.flush();
    }

    static void row(PrintStream out, double t, double[] reals, int mode, boolean contact) {
        StringBuilder line = new StringBuilder(String.format(Locale.ROOT, "%.17g", t));
        for (double value : reals) {
            line.append(String.format(Locale.ROOT, ",%.17g", value));
        }
        line.append(',').append(mode).append(',').append(contact ? 1 : 0);
        out.println(line);
    }

    static void fail(String what) {
        System.err.println(what);
        System.exit(1);
    }

    /** FMI4j: explicit fmi2DoStep(t_i, h) with t_i = i * h, as fmpy computes the grid. */
    static void runFmi4j(File file, double stop, int steps, PrintStream out) throws Exception {
        Fmu fmu = Fmu.from(file);
        try (CoSimulationSlave slave = fmu.asCoSimulationFmu().newInstance()) {
            // start 0, stop time, tolerance 0 = not defined: the FMU picks its own (1e-6 here)
            if (!slave.simpleSetup()) {
                fail("fmi4j: setup failed: " + slave.getLastStatus());
            }
            double h = stop / steps;
            double[] reals = new double[REALS.length];
            int[] mode = new int[1];
            boolean[] contact = new boolean[1];
            for (int i = 0; i <= steps; i++) {
                if (i > 0 && !slave.doStep((i - 1) * h, h)) {
                    fail("fmi4j: fmi2DoStep at t = " + (i - 1) * h + " failed: " + slave.getLastStatus());
                }
                slave.readReal(REAL_VRS, reals);
                slave.readInteger(MODE_VR, mode);
                slave.readBoolean(CONTACT_VR, contact);
                row(out, i * h, reals, mode[0], contact[0]);
            }
            slave.terminate();
        } finally {
            fmu.close();
        }
    }

    /** JavaFMI: Simulation.doStep(h), the wrapper keeps the time. */
    static void runJavaFmi(File file, double stop, int steps, PrintStream out) {
        Simulation simulation = new Simulation(file.getPath());
        Status status = simulation.init(0.0, stop);
        if (status != Status.OK) {
            fail("javafmi: init returned " + status);
        }
        double h = stop / steps;
        double[] reals = new double[REALS.length];
        for (int i = 0; i <= steps; i++) {
            if (i > 0) {
                status = simulation.doStep(h);
                if (status != Status.OK) {
                    fail("javafmi: doStep at t = " + simulation.getCurrentTime() + " returned " + status);
                }
            }
            for (int k = 0; k < REALS.length; k++) {
                reals[k] = simulation.read(REALS[k]).asDouble();
            }
            row(out, simulation.getCurrentTime(), reals, simulation.read("mode").asInteger(),
                simulation.read("contact").asBoolean());
        }
        simulation.terminate();
    }
}
